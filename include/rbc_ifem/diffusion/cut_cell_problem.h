#ifndef rbc_ifem_diffusion_cut_cell_problem_h
#define rbc_ifem_diffusion_cut_cell_problem_h

#include <rbc_ifem/diffusion/cut_cell_geometry.h>
#include <rbc_ifem/diffusion/cut_cell_terms.h>
#include <rbc_ifem/diffusion/diffusion_solver.h>
#include <rbc_ifem/diffusion/parameters.h>

#include <deal.II/base/index_set.h>
#include <deal.II/base/timer.h>
#include <deal.II/fe/fe.h>
#include <deal.II/hp/fe_collection.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/trilinos_precondition.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>
#include <deal.II/non_matching/fe_values.h>
#include <deal.II/numerics/data_out.h>

#include <functional>
#include <memory>
#include <vector>

namespace rbc_ifem
{
  /**
   * What the cut-cell uptake problems share (CutCellDiffusion, the
   * membrane sink; CutCellReaction, the reaction inside the cells), on the
   * CutCellGeometry they are given:
   * - Q_k fields on the mesh cells that reach into their side of the
   *   membranes (FE_Nothing on the others), the constraints of P (hanging
   *   nodes, P = P_A on the alveolar surface, periodic ends), and the
   *   sparsity with the couplings of the ghost penalty's faces;
   * - the assembly: a loop over the cells, whose terms each problem lists
   *   (cut_cell_terms.h), and one over the faces of cut cells with the ghost
   *   penalty of every field on both sides;
   * - the solve: the system is symmetric positive definite, CG with one AMG
   *   V-cycle, symmetrically Jacobi-scaled (DiagonallyScaled);
   * - the CO flux into each membrane, the consistent Nitsche flux
   *   j = −{αD ∂ₙP} + β [P] on Γh, each surface quadrature point giving its
   *   share to the membrane closest to it; the flux map on a membrane is the
   *   lumped L² projection of j onto FE_Q<2,3>(1) there. Its integral over
   *   the whole Γh equals the flow through the alveolar surface exactly
   *   (test with q = 1);
   * - the output: P, the signed distance and the material id, and the flux
   *   map on the membranes.
   *
   * A new problem on cut cells (another gas, another binding) is a sibling:
   * a class derived from this one that says which fields live on a cell,
   * which terms act there and how the membrane couples them.
   */
  class CutCellProblem : public DiffusionSolver
  {
  public:
    ~CutCellProblem() override;

    void
    assemble() override;

    /// Solve for P; throws SolverFailure if CG does not converge.
    void
    solve() override;

    /// The DoFs of the fields, less those held at zero outside their side.
    types::global_dof_index
    n_dofs() const override;

    /**
     * P on the cells that reach into the plasma, with the signed distance
     * to the membranes as "membrane_distance" [µm] (> 0 in the plasma) and
     * the material id; the membranes with the flux map j.
     */
    OutputFiles
    write_output(const std::string &directory,
                 const std::string &name,
                 const unsigned int counter    = 0,
                 const FieldData   &field_data = {}) const override;

    /**
     * The flux map of the last solve, what write_output() writes: on each
     * membrane (in the order of the geometry's MembraneSurfaces) the
     * lumped L² projection of the flux j onto FE_Q<2,3>(1), j_i = ∫ j μ_i /
     * ∫ μ_i, with the DoFs of a DoFHandler of FE_Q<2,3>(1) on the membrane's
     * mesh [µm³ µm⁻² s⁻¹ at the run's P_A]. Its integral is the membrane's
     * flow. The ranks' parts of ∫ j μ_i are summed in one reduction for all
     * membranes, once per call (collective): only output needs it.
     */
    std::vector<Vector<double>>
    flux_map() const;

  protected:
    /**
     * The problem of @p parameters on @p geometry (which must outlive it),
     * with αD = @p permeability(material id) and P = P_A on boundary
     * @p pressure_boundary.
     */
    CutCellProblem(const CutCellGeometry                     &geometry,
                   const DiffusionParameters                 &parameters,
                   const std::function<double(unsigned int)> &permeability,
                   const types::boundary_id                   pressure_boundary,
                   TimerOutput                               &timer);

    /**
     * Distribute the DoFs of @p fe, the problem's fields (FE_Q(k) or a
     * system of them), on the cells where fields_on() is not empty, make
     * the constraints and the sparsity pattern. Derived classes call it
     * from their constructor.
     */
    void
    set_up_system(const FiniteElement<3> &fe);

    /// The fields (0 the plasma's) that live on @p cell: those whose side
    /// of the membranes it reaches into, in increasing order.
    virtual std::vector<unsigned int>
    fields_on(const Triangulation<3>::cell_iterator &cell) const = 0;

    /// What the cell terms need of each region of a cut cell.
    virtual NonMatching::RegionUpdateFlags
    assembly_flags() const = 0;

    /**
     * Add the problem's terms on the locally owned @p cell, whose
     * @p values are reinit'ed, to @p matrix (the membrane's too, with
     * membrane_coupling()).
     */
    virtual void
    add_cell_terms(const NonMatching::FEValues<3>            &values,
                   const DoFHandler<3>::active_cell_iterator &cell,
                   const CutCellShapes                       &shapes,
                   FullMatrix<double>                        &matrix) const = 0;

    /// The Nitsche coefficients on @p cell: the assembly's and the flux's.
    virtual MembraneCoupling
    membrane_coupling(
      const DoFHandler<3>::active_cell_iterator &cell) const = 0;

    /**
     * αD of field @p field on @p cell, the ghost penalty's weight: the
     * plasma's material's, unless a problem with fields inside the cells
     * says otherwise.
     */
    virtual double
    field_permeability(const unsigned int                         field,
                       const DoFHandler<3>::active_cell_iterator &cell) const;

    /// γ_N k(k+1)/h on @p cell: the Nitsche penalty per αD [1/µm].
    double
    nitsche_weight(const DoFHandler<3>::active_cell_iterator &cell) const;

    /// Add P to @p data_out: the plasma's field as "co_pressure".
    virtual void
    add_pressure_fields(DataOut<3> &data_out) const;

    /**
     * The pressure fields of a problem with fields inside the cells on
     * @p cell: 0 (the plasma's) where it reaches into the plasma, and
     * 1 + the colour of the red cell it reaches into, if any.
     */
    std::vector<unsigned int>
    plasma_and_cell_fields(const Triangulation<3>::cell_iterator &cell) const;

    /// The name of the flux map in the output: "co_flux".
    virtual std::string
    flux_name() const;

    /**
     * The fields on @p cell that are a pressure, which the membrane
     * couples: fields_on(), unless a problem has fields that do not cross
     * the membranes (CutCellOxygen's saturation).
     */
    virtual std::vector<unsigned int>
    pressure_fields_on(const Triangulation<3>::cell_iterator &cell) const;

    /// The matrix and right-hand side of the cell terms and the ghost
    /// penalty, assembled, without the preconditioner.
    void
    assemble_operator();

    /**
     * Call @p f(values, cell) on every locally owned cell with fields,
     * @p values the cut-cell values with @p flags reinit'ed on it: the
     * loop of the assembly, for problems that integrate more.
     */
    void
    for_each_field_cell(
      const NonMatching::RegionUpdateFlags &flags,
      const std::function<void(const NonMatching::FEValues<3> &,
                               const DoFHandler<3>::active_cell_iterator &)> &f)
      const;

    /// The flows into the membranes and this rank's part of the flux map
    /// (projections), from the solution.
    void
    compute_flows();

    const CutCellGeometry                    &geometry;
    const DiffusionParameters                 parameters;
    const std::function<double(unsigned int)> permeability;
    const types::boundary_id                  pressure_boundary;
    const MPI_Comm                            communicator;
    TimerOutput                              &timer;

    DoFHandler<3>                 dof_handler;
    TrilinosWrappers::MPI::Vector solution;
    IndexSet                      owned_dofs, relevant_dofs;
    /// Hanging nodes, P = P_A on the pressure boundary, periodic ends and
    /// the unused fields' DoFs held at zero.
    AffineConstraints<double> constraints;
    /// The operator of the cell terms and the ghost penalty, and its
    /// right-hand side (P = P_A lifted).
    TrilinosWrappers::SparseMatrix matrix;
    TrilinosWrappers::MPI::Vector  rhs;

  private:
    /// The DoFs of this rank's cells (and their ghosts) that belong to a
    /// field outside its cells, held at zero.
    IndexSet
    unused_field_dofs() const;
    void
    set_up_matrix();
    void
    assemble_cells();
    void
    assemble_ghost_penalty();
    /// Hold at zero the DoFs whose rows assembled only round-off.
    void
    hold_unsupported_dofs();
    void
    build_preconditioner();
    /// The shape functions of @p cell by side, for the terms.
    CutCellShapes
    shapes_on(const DoFHandler<3>::active_cell_iterator &cell) const;
    /// The fields the ghost penalty acts on at @p face of @p cell: those on
    /// both sides, if at least one is cut.
    std::vector<unsigned int>
    ghost_penalty_fields(const DoFHandler<3>::active_cell_iterator &cell,
                         const unsigned int                         face) const;
    /**
     * Call @p f(cell, face) once for every face with a ghost penalty that
     * this rank assembles: from the finer side where the levels differ,
     * from the side with the smaller CellId where they do not.
     */
    template <typename Function>
    void
    for_each_ghost_penalty_face(const Function &f) const;
    /// The consistent Nitsche flux j = −{αD ∂ₙP} + β [P] into the
    /// membrane at each point of @p surface, the membrane part of @p cell.
    std::vector<double>
    membrane_flux(const NonMatching::FEImmersedSurfaceValues<3> &surface,
                  const DoFHandler<3>::active_cell_iterator     &cell) const;

    /// FE_Q(k) or a system of fields, and FE_Nothing.
    hp::FECollection<3> fe_collection;
    /// The number of DoFs held at zero (unused_field_dofs()), on all ranks.
    types::global_dof_index n_unused_dofs = 0;

    TrilinosWrappers::PreconditionAMG amg;

    /// The flux map's space, FE_Q<2,3>(1) on each membrane, and the
    /// integrals ∫ j μ_i over this rank's cut cells.
    std::vector<std::unique_ptr<DoFHandler<2, 3>>> flux_dof_handlers;
    std::vector<Vector<double>>                    projections;
  };
} // namespace rbc_ifem

#endif
