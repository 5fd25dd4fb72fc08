#ifndef rbc_ifem_membrane_membrane_h
#define rbc_ifem_membrane_membrane_h

#include <rbc_ifem/base/field_data.h>
#include <rbc_ifem/membrane/elastic_law.h>
#include <rbc_ifem/membrane/parameters.h>

#include <deal.II/base/mpi.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/base/table.h>
#include <deal.II/base/tensor.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/grid/tria.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/sparse_matrix.h>
#include <deal.II/lac/sparsity_pattern.h>
#include <deal.II/lac/vector.h>

#include <array>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace dealii
{
  template <int dim, int spacedim>
  class DataOut;
} // namespace dealii

namespace rbc_ifem
{
  using namespace dealii;

  /// The parts of a membrane's energy [pN µm].
  struct MembraneEnergy
  {
    double in_plane = 0.; ///< hyperelastic, ∫ W dA0
    double bending  = 0.; ///< Helfrich, κ/2 ∫ (2H - c0)² dA
    double area     = 0.; ///< k_A/2 (A - A0)²/A0
    double volume   = 0.; ///< k_V/2 (V - V0)²/V0

    double
    total() const
    {
      return in_plane + bending + area + volume;
    }
  };

  /**
   * The tangent stiffness K = ∂²E/∂x² of a Membrane at positions x, exact
   * for its discrete energy, so that the forces at x + δx are F - K δx to
   * first order (Membrane::stiffness()). Two parts: a sparse matrix on the
   * membrane's DoFs (the cell integrals, and the bending energy's nodal
   * sums, which couple the DoFs of all cells around a node), and the
   * rank-one terms c ∇S ∇Sᵀ of the area and volume penalties (S = A or V,
   * c = k/S0), which couple every DoF with every other and are kept as
   * vectors.
   */
  struct MembraneStiffness
  {
    /// The sparse part: this rank's share of it when the membrane shares
    /// its work (Membrane::share_work()).
    SparseMatrix<double>                           local;
    std::vector<std::pair<double, Vector<double>>> rank_one;
    /// The ranks that hold a share of the sparse part.
    MPI_Comm communicator = MPI_COMM_SELF;

    /// @p dst += K @p src; collective over the communicator.
    void
    vmult_add(Vector<double> &dst, const Vector<double> &src) const;

    /// @p diagonal += the diagonal of K; collective over the communicator.
    void
    add_diagonal(Vector<double> &diagonal) const;
  };

  /**
   * One red cell membrane: its position field x in
   * FESystem<2,3>(FE_Q<2,3>(k), 3) on the reference mesh (the Evans-Fung
   * Triangulation<2,3>), and its energy
   *
   *   E(x) = ∫ W(λ1, λ2) dA0 + κ/2 Σ_i m_i |y_i/m_i - c0 ν_i|²
   *        + k_A/2 (A - A0)²/A0 + k_V/2 (V - V0)²/V0,
   *
   * with every integral on the surface the field x describes (the
   * isoparametric map of each cell, as MappingFEField): the reference X is
   * the field interpolating the reference surface, stress-free in-plane. The
   * bending term is a mixed, mass-lumped form of the Helfrich energy
   * κ/2 ∫ (2H - c0)² dA, built on -Δ_Γ x = 2H n: y_i = ∫ ∇_Γ N_i · ∇_Γ x dA
   * is the weak Laplace-Beltrami operator of the position at node i, m_i =
   * ∫ N_i dA its lumped mass (so y_i/m_i approximates 2H n there) and ν_i the
   * unit nodal normal, from ∫ N_i n dA. A0, V0 are
   * the discrete reference area and volume. See doc/membrane.md.
   *
   * energy_and_forces() returns F = -∂E/∂x, exact for this discrete energy:
   * every term is a function of cell integrals and of nodal and global sums
   * of them, so the chain rule reduces the gradient to one derivative per
   * cell. Each integrand depends on the cell's DoFs only through the
   * position and tangents at its quadrature point (9 numbers), so that
   * derivative is taken there, with Sacado's forward-mode automatic
   * differentiation in those 9, and chained to the cell's DoFs.
   * stiffness() returns ∂²E/∂x², exact too: nested forward mode per point,
   * and the chain rule through the nodal and global sums.
   */
  class Membrane
  {
  public:
    /**
     * The membrane whose reference surface is @p reference. With @p like, a
     * membrane on a mesh of the same topology (the same reference shape
     * placed elsewhere, as every cell of a population), it shares like's
     * numbering of the DoFs and nodes and its stiffness's sparsity pattern
     * instead of making its own: the larger part of a membrane's memory
     * (a new numbering is made if the DoFs of a cell turn out otherwise).
     */
    Membrane(const Triangulation<2, 3> &reference,
             const MembraneParameters  &parameters,
             const Membrane            *like = nullptr);

    const DoFHandler<2, 3> &
    get_dof_handler() const;

    /**
     * Share the cell loops of energy_and_forces() and stiffness() out over
     * the ranks of @p comm: each rank takes a contiguous block of the cells
     * (and of the nodes), and the sums, the forces and the products with
     * the stiffness are added up over the ranks, so that every rank gets
     * the whole result. Every rank of @p comm must then call these
     * functions together, with the same positions. Without it (or with
     * MPI_COMM_SELF) a membrane works alone.
     */
    void
    share_work(const MPI_Comm comm);

    /**
     * Drop what only the cell's owner needs, its reference metric: made
     * again on the next energy or stiffness. For a rank that has handed
     * the cell to another (CellOwners::place()). The stiffness's sparsity
     * pattern, shared by the membranes made alike, stays once made.
     */
    void
    forget_owner_data();

    /// The reference positions X: every DoF's coordinate on the reference
    /// surface.
    const Vector<double> &
    reference_positions() const;

    /// The vector component (0, 1, 2 for x, y, z) a DoF describes.
    unsigned int
    component(const types::global_dof_index dof) const;

    /// The DoFs of the x, y and z coordinates of every node.
    const std::vector<std::array<types::global_dof_index, 3>> &
    nodes() const;

    MembraneEnergy
    energy(const Vector<double> &x) const;

    /// E(x), and F = -∂E/∂x in @p forces [pN], one entry per DoF.
    MembraneEnergy
    energy_and_forces(const Vector<double> &x, Vector<double> &forces) const;

    /**
     * The tangent stiffness K = ∂²E/∂x² at @p x into @p stiffness, its
     * sparse part on this membrane's sparsity (the DoFs of the cells around
     * each node coupled).
     */
    void
    stiffness(const Vector<double> &x, MembraneStiffness &stiffness) const;

    /// The lumped area m_i = ∫ N_i dA of every node (nodes()) on the surface x.
    std::vector<double>
    nodal_areas(const Vector<double> &x) const;

    /**
     * The nodal forces @p f (one entry per DoF) divided by the lumped area
     * of their node on the surface x (nodal_areas()): a force per unit area
     * [pN/µm²], the traction the membrane exerts, which unlike the nodal
     * force does not shrink as the mesh is refined.
     */
    Vector<double>
    force_densities(const Vector<double> &x, const Vector<double> &f) const;

    /**
     * The vector area w_i = ∫ N_i n dA of every node (nodes()) on the
     * surface x: the derivative of the enclosed volume by the node's
     * position, so -p w_i are the nodal forces of a pressure p.
     */
    std::vector<Tensor<1, 3>>
    nodal_vector_areas(const Vector<double> &x) const;

    /**
     * A/A0 - 1 of every cell of the membrane mesh on the surface x (A0 its
     * area on the reference surface): the local area change, which the
     * global area penalty does not hold.
     */
    Vector<double>
    local_area_changes(const Vector<double> &x) const;

    /// Area [µm²] and enclosed volume [µm³] of the surface x.
    double
    area(const Vector<double> &x) const;
    double
    volume(const Vector<double> &x) const;

    double
    reference_area() const;
    double
    reference_volume() const;

    /**
     * The deformed surface x as NAME.vtu in @p directory (the caller decides
     * which rank writes), curved by a MappingFEField on x, with the
     * displacement x - X and, as further vector fields, each (name, vector)
     * of @p dof_vectors (one entry per DoF, like the forces), and the
     * local area change A/A0 - 1 of every cell as the cell field
     * area_change; the file carries @p field_data.
     */
    void
    write_vtu(const Vector<double> &x,
              const std::string    &directory,
              const std::string    &name,
              const std::vector<std::pair<std::string, Vector<double>>>
                              &dof_vectors = {},
              const FieldData &field_data  = {}) const;

    /**
     * What write_vtu() writes, as the patches of @p data_out (a new one:
     * it is attached to this membrane and its patches built here), with
     * each (name, value) of @p cell_constants as one more cell field, the
     * same on every cell (a cell's index among many, say). DataOut's
     * merge_patches() joins the patches of several membranes into one file.
     */
    void
    build_patches(
      DataOut<2, 3>                                             &data_out,
      const Vector<double>                                      &x,
      const std::vector<std::pair<std::string, Vector<double>>> &dof_vectors,
      const std::vector<std::pair<std::string, double>> &cell_constants = {})
      const;

    /**
     * The surface x as a mesh with flat cells between its vertices (the
     * nodes, for k = 1, where that is the membrane itself): what the CO
     * diffusion solve takes as the membrane at this instant. @p surface is
     * replaced by a copy of the reference mesh with moved vertices.
     */
    void
    build_surface(const Vector<double> &x, Triangulation<2, 3> &surface) const;

  private:
    template <typename Number>
    struct CellTerms;
    struct Sums;
    struct Multipliers;
    struct ReferenceMetric;

    /// @name The constructor's steps, in this order
    /// @{
    /// N_a and ∂N_a/∂ξ at the quadrature points, and the point maps L_q.
    void
    tabulate_shape_functions();
    /// The nodes, numbered by the DoF of their x component, and every
    /// cell's DoFs and nodes: @p like's numbering if it numbers every cell's
    /// DoFs as this membrane's DoF handler does.
    void
    number_nodes(const Membrane *like);
    /// cells_around_node.
    void
    find_cells_around_nodes();
    /// X: the support points of the field, on the curved reference surface.
    void
    interpolate_reference_surface();
    /// Every cell's reference area, A0 and V0.
    void
    measure_reference_surface();
    /// @}

    /**
     * E from the sums, into @p energy, and the derivatives of E by every
     * sum: what turns the derivatives of the cell terms into E's.
     */
    Multipliers
    energy_derivatives(const Sums &sums, MembraneEnergy &energy) const;

    /**
     * The cell's share of E with the sums' derivatives @p d held fixed,
     * φ_c = W_c + d_A A_c + d_V V_c + Σ_a (d_y·y_a + d_m m_a + d_w·w_a):
     * its gradient in the cell's DoFs is E's, and its Hessian E's but for
     * the curvature of E in the sums themselves.
     */
    template <typename Number>
    Number
    cell_potential(const unsigned int       cell,
                   const CellTerms<Number> &terms,
                   const Multipliers       &d) const;

    struct PointWeights;

    /// How many integrands point_integrands() returns.
    static constexpr unsigned int n_point_integrands = 11;

    /**
     * The integrands of the cell terms at quadrature point @p q of cell
     * @p c, times its weight, from the point's position and tangents @p z:
     * dA, x·n dA/3, n dA (3) and g^{αβ} ∂x/∂ξβ dA for α = 1, 2 (3 each),
     * whose products with N_a and ∂N_a/∂ξα sum to the cell's m_a, V, w_a
     * and y_a (the area is the first).
     */
    template <typename Number>
    std::array<Number, n_point_integrands>
    point_integrands(const unsigned int           c,
                     const unsigned int           q,
                     const std::array<Number, 9> &z) const;

    /// The sums' derivatives @p d gathered at quadrature point @p q of
    /// cell @p c.
    PointWeights
    point_weights(const unsigned int c,
                  const unsigned int q,
                  const Multipliers &d) const;

    /**
     * The integrand of cell_potential() at quadrature point @p q of
     * @p cell, times its weight, from the point's position and tangents
     * @p z = (x, ∂x/∂ξ1, ∂x/∂ξ2) and the sums' derivatives gathered there.
     */
    template <typename Number, typename Law>
    Number
    point_potential(const Law                   &law,
                    const unsigned int           cell,
                    const unsigned int           q,
                    const std::array<Number, 9> &z,
                    const PointWeights          &weights) const;

    /// The reference metric at every quadrature point, made on the first
    /// call.
    const ReferenceMetric &
    reference_metric() const;

    /// The stiffness's sparsity, the DoFs of the cells around each node
    /// coupled, made on the first call.
    const SparsityPattern &
    stiffness_pattern() const;

    /// The DoFs of the cells around node @p i, sorted.
    std::vector<types::global_dof_index>
    patch_dofs(const unsigned int i) const;

    /// @name The steps of stiffness()
    /// @{
    struct SumGradients;

    /**
     * The cells whose first derivatives this rank's share of the stiffness
     * needs: its own cells (for ∂A/∂x and ∂V/∂x) and those around its
     * nodes (for their bending energy).
     */
    std::vector<bool>
    cells_for_sum_gradients() const;

    /// The first derivatives of the sums at @p x that the stiffness chains
    /// through, by forward mode at each quadrature point.
    SumGradients
    sum_gradients(const Vector<double> &x) const;

    /**
     * Add quadrature point @p q's share of the derivatives of a cell's
     * nodal sums (y, m, w) to @p J, from @p DL, the derivatives of
     * point_integrands() there by the cell's DoFs.
     */
    void
    add_nodal_sum_derivatives(const unsigned int        q,
                              const FullMatrix<double> &DL,
                              FullMatrix<double>       &J) const;

    /**
     * Add to @p K the Hessian of each of this rank's cells' potentials φ_c
     * (cell_potential()) with the sums' derivatives @p d held fixed,
     * H_c = Σ_q L_qᵀ H_q L_q, the 9 × 9 H_q by nested forward mode.
     */
    void
    add_cell_hessians(const Vector<double> &x,
                      const Multipliers    &d,
                      SparseMatrix<double> &K) const;

    /**
     * Add to @p K the bending energy's curvature in each of this rank's
     * nodes' sums s_i = (y, m, w): J_iᵀ B_i J_i, with J_i = ∂s_i/∂x over the
     * cells around the node (from @p nodal_sum_gradients, as
     * SumGradients holds them).
     */
    void
    add_bending_curvature(
      const Sums                            &sums,
      const std::vector<FullMatrix<double>> &nodal_sum_gradients,
      SparseMatrix<double>                  &K) const;
    /// @}

    /// The integrals of one cell at the local positions @p x, with @p law.
    template <typename Number, typename Law>
    CellTerms<Number>
    cell_terms(const Law                 &law,
               const unsigned int         cell,
               const std::vector<Number> &x) const;

    /// Add the terms of @p cell to the nodal and global @p sums.
    void
    add_cell_terms(const unsigned int       cell,
                   const CellTerms<double> &terms,
                   Sums                    &sums) const;

    /// The cell integrals summed: per node (y, m, ν) and global (A, V).
    Sums
    sum_cell_terms(const Vector<double> &x) const;

    /// The same over the cells [@p cells.first, @p cells.second) only.
    Sums
    sum_cell_terms(const Vector<double>                       &x,
                   const std::pair<unsigned int, unsigned int> cells) const;

    /// sum_cell_terms() shared out over the ranks of share_work().
    Sums
    sum_shared_cell_terms(const Vector<double> &x) const;

    /// This rank's block [first, second) of @p n items shared out.
    std::pair<unsigned int, unsigned int>
    share(const unsigned int n) const;

    std::vector<double>
    local_positions(const unsigned int cell, const Vector<double> &x) const;

    const MembraneParameters parameters;
    const ElasticLaw         elastic_law; ///< chosen from parameters.law
    MPI_Comm                 communicator = MPI_COMM_SELF; ///< share_work()
    FE_Q<2, 3>               scalar_fe;
    FESystem<2, 3>           fe;
    DoFHandler<2, 3>         dof_handler;
    QGauss<2>                quadrature;
    Vector<double>           reference;

    /**
     * What depends only on the mesh's topology, not on where it is: the
     * numbering of the DoFs and nodes and the stiffness's sparsity
     * pattern. Membranes on one reference shape placed in several places
     * (the cells of a population) share one (the constructor's @p like).
     */
    struct Numbering
    {
      /// Per cell: its DoFs, and per local DoF the node (a cell-local base
      /// function) and the global node number.
      std::vector<std::vector<types::global_dof_index>>   cell_dofs;
      std::vector<std::vector<unsigned int>>              cell_nodes;
      unsigned int                                        n_nodes = 0;
      std::vector<unsigned int>                           component_of_dof;
      std::vector<std::array<types::global_dof_index, 3>> node_dofs;
      /// Per node, the (cell, local node) pairs of the cells around it.
      std::vector<std::vector<std::pair<unsigned int, unsigned int>>>
        cells_around_node;
      /// The DoFs coupled by the stiffness: those of the cells around a
      /// node (stiffness_pattern()), made on the first stiffness of any
      /// membrane that shares it.
      SparsityPattern stiffness_sparsity;
    };
    /// Shared with the membranes made like this one; the stiffness pattern
    /// in it is filled in lazily, hence not const.
    std::shared_ptr<Numbering> numbering;

    /// Reference geometry per cell and quadrature point: G⁻¹ and sqrt(det G).
    struct ReferenceMetric
    {
      std::vector<std::vector<Tensor<2, 2>>> inverse;
      std::vector<std::vector<double>>       jacobian;
    };
    /// Made when an energy or measure first needs it (reference_metric()),
    /// and dropped after the constructor's measures: a membrane made and
    /// kept for what depends on its shape alone (the model of a
    /// CellPopulation) makes it on its first measure.
    mutable ReferenceMetric metric;

    /// N_a and ∂N_a/∂ξ at the quadrature points of the unit cell.
    Table<2, double>       shape_values;
    Table<2, Tensor<1, 2>> shape_gradients;
    /// Per quadrature point q, the 9 × (cell DoFs) matrix L_q taking a
    /// cell's positions to the point's position and tangents
    /// z = (x, ∂x/∂ξ1, ∂x/∂ξ2): what the energy density depends on.
    std::vector<FullMatrix<double>> point_maps;

    /// Every cell's area on the reference surface [µm²].
    std::vector<double> reference_cell_areas;
    double              area0   = 0.;
    double              volume0 = 0.;
  };
} // namespace rbc_ifem

#endif
