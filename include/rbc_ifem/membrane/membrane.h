#ifndef rbc_ifem_membrane_membrane_h
#define rbc_ifem_membrane_membrane_h

#include <rbc_ifem/base/field_data.h>
#include <rbc_ifem/membrane/elastic_law.h>
#include <rbc_ifem/membrane/parameters.h>

#include <deal.II/base/quadrature_lib.h>
#include <deal.II/base/table.h>
#include <deal.II/base/tensor.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/grid/tria.h>
#include <deal.II/lac/vector.h>

#include <array>
#include <string>
#include <utility>
#include <vector>

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
   * cell, taken with Sacado's forward-mode automatic differentiation.
   */
  class Membrane
  {
  public:
    Membrane(const Triangulation<2, 3> &reference,
             const MembraneParameters  &parameters);

    const DoFHandler<2, 3> &
    get_dof_handler() const;

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

    /// The lumped area m_i = ∫ N_i dA of every node (nodes()) on the surface x.
    std::vector<double>
    nodal_areas(const Vector<double> &x) const;

    /**
     * The vector area w_i = ∫ N_i n dA of every node (nodes()) on the
     * surface x: the derivative of the enclosed volume by the node's
     * position, so -p w_i are the nodal forces of a pressure p.
     */
    std::vector<Tensor<1, 3>>
    nodal_vector_areas(const Vector<double> &x) const;

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
     * of @p dof_vectors (one entry per DoF, like the forces); the file
     * carries @p field_data.
     */
    void
    write_vtu(const Vector<double> &x,
              const std::string    &directory,
              const std::string    &name,
              const std::vector<std::pair<std::string, Vector<double>>>
                              &dof_vectors = {},
              const FieldData &field_data  = {}) const;

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

    std::vector<double>
    local_positions(const unsigned int cell, const Vector<double> &x) const;

    const MembraneParameters parameters;
    const ElasticLaw         elastic_law; ///< chosen from parameters.law
    FE_Q<2, 3>               scalar_fe;
    FESystem<2, 3>           fe;
    DoFHandler<2, 3>         dof_handler;
    QGauss<2>                quadrature;
    Vector<double>           reference;

    /// Per cell: its DoFs, and per local DoF the node (a cell-local base
    /// function) and the global node number.
    std::vector<std::vector<types::global_dof_index>>   cell_dofs;
    std::vector<std::vector<unsigned int>>              cell_nodes;
    unsigned int                                        n_nodes = 0;
    std::vector<unsigned int>                           component_of_dof;
    std::vector<std::array<types::global_dof_index, 3>> node_dofs;

    /// Reference geometry per cell and quadrature point: G⁻¹ and sqrt(det G).
    std::vector<std::vector<Tensor<2, 2>>> reference_metric_inverse;
    std::vector<std::vector<double>>       reference_jacobian;

    /// N_a and ∂N_a/∂ξ at the quadrature points of the unit cell.
    Table<2, double>       shape_values;
    Table<2, Tensor<1, 2>> shape_gradients;

    double area0   = 0.;
    double volume0 = 0.;
  };
} // namespace rbc_ifem

#endif
