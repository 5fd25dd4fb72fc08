#ifndef rbc_ifem_diffusion_cut_cell_diffusion_h
#define rbc_ifem_diffusion_cut_cell_diffusion_h

#include <rbc_ifem/diffusion/diffusion_solver.h>
#include <rbc_ifem/diffusion/membrane_distance.h>
#include <rbc_ifem/diffusion/parameters.h>

#include <deal.II/base/index_set.h>
#include <deal.II/base/timer.h>
#include <deal.II/distributed/tria_base.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/mapping_q_cache.h>
#include <deal.II/grid/cell_id.h>
#include <deal.II/hp/fe_collection.h>
#include <deal.II/hp/mapping_collection.h>
#include <deal.II/hp/q_collection.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/la_parallel_vector.h>
#include <deal.II/lac/trilinos_precondition.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/non_matching/fe_values.h>
#include <deal.II/non_matching/mesh_classifier.h>

#include <map>
#include <memory>
#include <optional>
#include <stdexcept>
#include <utility>
#include <vector>

namespace rbc_ifem
{
  /**
   * Cut cells of the diffusion mesh that the level set cannot resolve,
   * thrown by CutCellDiffusion::setup() on every rank, with every such
   * cell, so that the caller can refine them and try again:
   * - two membranes pass through one cell: the gap between them is
   *   narrower than the mesh, and the level set cannot tell them apart
   *   (membranes names two of them);
   * - the distance to a membrane has a ridge inside a cut cell, where two
   *   sides of the membrane are equally far (the cell reaches across a thin
   *   part of the red cell, the biconcave dimple or a parachute's fold): the
   *   polynomial level set smooths the ridge's kink and moves the membrane.
   *   (The ridges between two membranes, in the plasma, are left alone:
   *   refining every gap costs three times the DoFs of seven cells for a
   *   quarter of a percent of DM.)
   */
  class UnresolvedCutCells : public std::runtime_error
  {
  public:
    UnresolvedCutCells(
      std::vector<CellId>                                         cells,
      const std::optional<std::pair<unsigned int, unsigned int>> &membranes);

    /// The mesh cells, on every rank.
    const std::vector<CellId> cells;
    /// Two membranes (indices into the membranes) that share a cell, if
    /// any do.
    const std::optional<std::pair<unsigned int, unsigned int>> membranes;
  };

  /**
   * Steady CO uptake on cut cells (Diffusion/Method = cut cell): the plasma
   * is the part of the diffusion mesh outside every red cell, described by a
   * level set, and P = 0 holds on its boundary, the membranes, by Nitsche's
   * method, as in deal.II's step-85:
   *
   *   find P in Q_k on the cells that reach into the plasma such that
   *   (αD ∇P, ∇q)_Ωh − (αD ∂ₙP, q)_Γh − (αD ∂ₙq, P)_Γh
   *     + (γ_N k(k+1) αD/h P, q)_Γh + g(P, q) = 0   for all q,
   *
   * with n the normal out of the plasma on the discrete membranes Γh and the
   * ghost penalty g(P, q) = Σ_F Σ_{j=1..k} γ_g αD h^(2j−1) ([∂ₙʲP], [∂ₙʲq])_F
   * on the faces F of cut cells, which bounds the condition number however
   * the membranes cut the cells.
   *
   * The level set φ is the Q_k interpolant of minus the signed distance to
   * the membranes (MembraneDistance), so Γh = {φ = 0} is within O(h^(k+1))
   * of them, and the quadratures on the cut cells come from deal.II's
   * NonMatching::FEValues (Saye's algorithm). P has no kink inside any cell
   * (the cell interiors are not part of the problem), so DM converges at the
   * order of the geometry and the symmetric, adjoint-consistent Nitsche
   * flux: about k + 1.
   *
   * The CO flux into a membrane is the consistent Nitsche flux
   * j = −αD ∂ₙP + γ_N k(k+1) αD/h P on Γh. Its integral over the whole Γh
   * equals the flow through the alveolar surface exactly (test with q = 1);
   * each surface quadrature point gives its share to the membrane closest to
   * it, and the flux map on a membrane is the lumped L² projection of j onto
   * FE_Q<2,3>(1) there.
   *
   * The system is symmetric positive definite: CG with one AMG V-cycle,
   * symmetrically Jacobi-scaled (DiagonallyScaled).
   */
  class CutCellDiffusion : public DiffusionSolver
  {
  public:
    /// The arguments of CODiffusion's constructor.
    CutCellDiffusion(const DiffusionParameters                 &parameters,
                     const std::function<double(unsigned int)> &permeability,
                     const types::boundary_id     pressure_boundary,
                     const MPI_Comm               communicator,
                     TimerOutput                 &timer,
                     const std::optional<double> &period = std::nullopt);
    ~CutCellDiffusion() override;

    /**
     * Build the level set of the membranes, classify the cells, distribute
     * the DoFs on the cells that reach into the plasma, find each surface
     * quadrature point's membrane. Throws InputError if a membrane leaves
     * the lumen, UnresolvedCutCells if two pass through one mesh cell, if
     * (with separate_insides()) the nodes of a cut cell are closest to two
     * membranes, or (unless refine_ridges(false)) the distance has a ridge
     * in a cut cell.
     * @p mesh is shared or fully distributed: each rank works on the cells
     * it owns and the ghost layer around them.
     */
    void
    setup(const parallel::TriangulationBase<3>           &mesh,
          const std::vector<const Triangulation<2, 3> *> &membranes,
          const MappingQ<2, 3> &membrane_mapping) override;

    /**
     * Whether setup() asks for the cut cells with a ridge of the distance
     * to be refined (default true). The caller switches it off after the
     * last refinement it allows: the ridges are then resolved as well as
     * the mesh resolves them.
     */
    void
    refine_ridges(const bool refine);

    /**
     * Whether setup() treats a cut cell whose level set nodes are closest
     * to two membranes as one that two membranes pass through (default
     * false; always with react_inside_cells()). The level set smooths the
     * ridge of the distance between two membranes in such a cell, and where
     * they are closer than about two cells the smoothed level set joins
     * their insides across the gap: seven cells at band refinements 1 then
     * hold 17% more volume. The plasma side barely notices (DM moves by
     * 0.2%), the reaction inside the cells does.
     */
    void
    separate_insides(const bool separate);

    /**
     * Take the distance to the membranes from @p distance, built by the
     * caller for the membranes that setup() will be given, instead of
     * sampling them in setup(): a caller that sets up on several meshes
     * around the same membranes samples them once, and finds each closest
     * point once (MembraneDistance remembers them).
     */
    void
    share_membrane_distance(std::shared_ptr<const MembraneDistance> distance);

    /**
     * Solve for finite uptake instead of P = 0 on the membranes
     * (Diffusion/Uptake = reaction); call before setup(). CO diffuses on
     * through the membranes into the cells, whose cytoplasm has the
     * permeability @p cell_permeability (αD, µm²/(s Torr)) and binds it at
     * the rate k P per unit volume (@p rate = k, s⁻¹ Torr⁻¹):
     *
     *   −∇·(αD ∇P) = 0 in the plasma,  −∇·(α_c D_c ∇P) + k P = 0 in the
     *   cells,  P and the flux continuous across the membranes.
     *
     * Each side has its own field (P₀ on the mesh cells that reach into the
     * plasma, P₁ on those that reach into a red cell, the DoFs of a field
     * outside its cells held at zero), glued by the symmetric Nitsche terms
     * of Hansbo & Hansbo (2002):
     *
     *   − ({αD ∂ₙP}, [q])_Γh − ([P], {αD ∂ₙq})_Γh + (β [P], [q])_Γh,
     *
     * [P] = P₀ − P₁, {αD ∂ₙP} = w₀ αD ∂ₙP₀ + w₁ α_cD_c ∂ₙP₁, and each
     * field has its ghost penalty. The weights w₀ = κ'/(αD + κ'),
     * w₁ = 1 − w₀ take the flux from the side that resolves it: Hansbo's
     * κ' = α_cD_c where the reaction is slow on the scale of the mesh, and
     * with κ' = α_cD_c √(1 + (m h)²), m² = k/(α_cD_c), the plasma's as
     * the reaction's boundary layer inside the membrane (thickness 1/m)
     * becomes thinner than the cells: as k → ∞ the problem becomes the
     * membrane sink's (P₁ → 0) and so does the discrete one.
     * β = 2 γ_N k(k+1) (w₀² αD + w₁² α_cD_c)/h. The flows are then the CO
     * bound inside each cell (the flux j = −{αD ∂ₙP} + β [P] into it,
     * summed over its membrane; over all membranes it equals ∫ k P₁), and
     * dm_total() is DL.
     *
     * P₁ of two red cells whose mesh cells touch must not share DoFs (a
     * thin plasma gap would join their insides, and their ghost penalties):
     * the red cells are coloured so that such neighbours differ, and each
     * colour has a field of its own, FESystem(FE_Q(k), 1 + colours).
     */
    void
    react_inside_cells(const double cell_permeability, const double rate);

    void
    assemble() override;

    /// Solve for P; throws SolverFailure if CG does not converge.
    void
    solve() override;

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

  private:
    /// Which membrane each surface quadrature point of a cut cell is on.
    using SurfacePoints = std::vector<MembraneDistance::ClosestPoint>;

    /**
     * The mapping's support points of the cells this rank evaluates on
     * (owned and ghost), placed on the capillary's manifolds once per mesh:
     * every FEValues reinit would otherwise place them again, several times
     * per cell.
     */
    void
    cache_mapping();
    void
    compute_level_set();
    /**
     * The level set nodes of the cells this rank owns and their positions,
     * each placed by the cell with the smallest CellId that holds it (the
     * cells' mappings differ in the last digits), so that the ranks that
     * share a node, and any number of ranks, place it alike.
     */
    std::vector<std::pair<types::global_dof_index, Point<3>>>
    level_set_nodes() const;
    /// The cut cells of this rank that the distance has a ridge in: two of
    /// their level set nodes whose closest points on one membrane face
    /// opposite ways.
    std::vector<CellId>
    ridge_cells() const;

    /// Cut cells of this rank that two membranes pass through, and two such
    /// membranes (equal if there are none).
    struct SharedCells
    {
      std::vector<CellId>                   cells;
      std::pair<unsigned int, unsigned int> membranes{0, 0};
    };

    /**
     * Find each surface quadrature point's membrane, and the cut cells that
     * two membranes share. Throws InputError if a membrane reaches into
     * the vessel wall or cuts no cell.
     */
    SharedCells
    locate_surface_points();

    /// With separate_insides(): add to @p shared the cut cells of this rank
    /// whose level set nodes are closest to two membranes.
    void
    add_gap_cells(SharedCells &shared) const;

    /// Throw UnresolvedCutCells, on every rank, if any rank found
    /// @p ridges or @p shared cells.
    void
    throw_if_unresolved(const std::vector<CellId> &ridges,
                        const SharedCells         &shared) const;

    void
    distribute_dofs();
    void
    setup_matrix();
    void
    assemble_cells();
    void
    assemble_ghost_penalty();
    /// Hold at zero the DoFs whose rows assembled only round-off.
    void
    hold_unsupported_dofs();
    void
    compute_flows();

    /// The fields (0 the plasma's, 1 the cells' with a reaction) that live
    /// on @p cell: those whose side of the membranes it reaches into.
    std::vector<unsigned int>
    fields_on(const Triangulation<3>::cell_iterator &cell) const;

    /// The fields the ghost penalty acts on at @p face of @p cell: those on
    /// both sides, if at least one is cut.
    std::vector<unsigned int>
    ghost_penalty_fields(const DoFHandler<3>::active_cell_iterator &cell,
                         const unsigned int                         face) const;

    /// With a reaction: the DoFs of this rank's cells (and their ghosts)
    /// that belong to a field outside its cells, held at zero.
    IndexSet
    unused_field_dofs() const;

    /// With a reaction: the red cell (membrane) that each mesh cell of this
    /// rank and its ghost layer reaches into, if any (cell_membrane).
    void
    find_cell_membranes();

    /// With a reaction: colour the membranes so that two whose mesh cells
    /// touch (across the periodic ends too) differ, and build the FE of
    /// 1 + colours fields.
    void
    colour_membranes();

    /**
     * Call @p f(cell, face) once for every face with a ghost penalty that
     * this rank assembles: from the finer side where the levels differ,
     * from the side with the smaller CellId where they do not.
     */
    template <typename Function>
    void
    for_each_ghost_penalty_face(const Function &f) const;

    /// FEValues on the plasma part and on the membrane part of each cell.
    std::unique_ptr<NonMatching::FEValues<3>>
    cut_cell_values(const NonMatching::RegionUpdateFlags &flags) const;

    /// The coefficients of the Nitsche terms on the membrane in a cell.
    struct MembraneCoupling
    {
      /// The flux {αD ∂ₙP} = plasma_flux ∂ₙP₀ + cell_flux ∂ₙP₁ [µm²/(s Torr)].
      double plasma_flux;
      double cell_flux;
      /// The penalty on [P] [µm/(s Torr)].
      double penalty;
    };

    /**
     * The Nitsche coefficients on @p cell: for the membrane sink αD, 0 and
     * γ_N k(k+1) αD/h; with a reaction w₀ αD, w₁ α_cD_c and
     * 2 γ_N k(k+1) (w₀² αD + w₁² α_cD_c)/h.
     */
    MembraneCoupling
    membrane_coupling(const DoFHandler<3>::active_cell_iterator &cell) const;

    const DiffusionParameters                 parameters;
    const std::function<double(unsigned int)> permeability;
    const types::boundary_id                  pressure_boundary;
    const std::optional<double>               period;
    const MPI_Comm                            communicator;
    TimerOutput                              &timer;

    const parallel::TriangulationBase<3>    *mesh = nullptr;
    std::vector<const Triangulation<2, 3> *> membranes;
    const MappingQ<2, 3>                    *membrane_mapping = nullptr;
    std::shared_ptr<const MembraneDistance>  shared_distance;
    std::shared_ptr<const MembraneDistance>  distance;

    MappingQCache<3>         mapping;
    hp::MappingCollection<3> mapping_collection;
    /// On uncut cells, and the 1-D rule of the cut cells' quadratures.
    const hp::QCollection<3> cell_quadrature;
    const hp::QCollection<1> line_quadrature;
    const FE_Q<3>            level_set_fe;
    DoFHandler<3>            level_set_dof_handler;
    /// φ = −(signed distance): < 0 in the plasma (deal.II's "inside"), on
    /// the nodes of the cells this rank owns and their ghost neighbours.
    LinearAlgebra::distributed::Vector<double> level_set;
    /// The membrane closest to each level set node of the cells this rank
    /// owns, and the outward normal at the closest point.
    std::map<types::global_dof_index, MembraneDistance::ClosestPoint>
         closest_points;
    bool ridge_refinement = true;
    bool separate_cells   = false;

    /// The cytoplasm's αD and binding rate k (react_inside_cells()).
    struct CellReaction
    {
      double permeability;
      double rate;
    };
    std::optional<CellReaction> reaction;
    /// With a reaction: the membrane each active mesh cell reaches into
    /// (by active cell index; invalid for the plasma's), and each
    /// membrane's colour: its inside is field 1 + colour.
    std::vector<unsigned int> cell_membrane, membrane_colour;
    std::unique_ptr<NonMatching::MeshClassifier<3>> classifier;

    /// FE_Q(k) and FE_Nothing, FESystem(FE_Q(k), 2) and FE_Nothing(2) with
    /// a reaction.
    hp::FECollection<3> fe_collection;
    /// The number of DoFs held at zero (unused_field_dofs()), on all ranks.
    types::global_dof_index               n_unused_dofs = 0;
    DoFHandler<3>                         dof_handler;
    IndexSet                              owned_dofs, relevant_dofs;
    AffineConstraints<double>             constraints;
    std::map<unsigned int, SurfacePoints> surface_points; ///< by cell index

    TrilinosWrappers::SparseMatrix    matrix;
    TrilinosWrappers::MPI::Vector     rhs, solution;
    TrilinosWrappers::PreconditionAMG amg;

    /// The flux map, FE_Q<2,3>(1) on each membrane.
    std::vector<std::unique_ptr<DoFHandler<2, 3>>> flux_dof_handlers;
    std::vector<Vector<double>>                    flux_map;
  };
} // namespace rbc_ifem

#endif
