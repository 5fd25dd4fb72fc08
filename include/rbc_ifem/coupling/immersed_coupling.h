#ifndef rbc_ifem_coupling_immersed_coupling_h
#define rbc_ifem_coupling_immersed_coupling_h

#include <rbc_ifem/fluid/fluid_vectors.h>

#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/mapping.h>
#include <deal.II/grid/grid_tools_cache.h>
#include <deal.II/grid/tria.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/particles/particle_handler.h>

#include <optional>
#include <vector>

namespace rbc_ifem
{
  using namespace dealii;

  /**
   * The immersed coupling of membranes and plasma (doc/design.md, "Immersed
   * coupling", steps 3 and 5): the membrane points, every node of every
   * cell, as the particles of a Particles::ParticleHandler<3> on the fluid
   * mesh, with the point's index as the particle id. The handler knows each
   * point's fluid cell and reference position, and hands points over
   * between cells and ranks as they move.
   *
   * Both directions use the same values φ_J(x_I) of the fluid's velocity
   * shape functions at the points:
   *
   *   spreading      f_J = Σ_I F_I · φ_J(x_I),
   *   interpolation  v_I = Σ_J v_J φ_J(x_I),
   *
   * so they are adjoint, ⟨f, v⟩ = Σ_I F_I · v_I: the power the membranes
   * put into the fluid is the power the fluid does on them. Since the
   * velocity space holds the constants and (Q2) the linear functions,
   * spreading keeps the total force and the total torque.
   *
   * The membranes are small, so every rank keeps the positions, forces and
   * velocities of all points (the same on every rank); a rank computes only
   * with the particles in its own cells, and interpolated velocities are
   * summed over the ranks.
   */
  class ImmersedCoupling
  {
  public:
    /**
     * @p velocity_dof_handler is the fluid's velocity space. With
     * a @p period along x (a periodic segment), every point is placed where
     * it lies in the segment (wrap_into_segment()): a membrane stays whole
     * for its mechanics while its points are found, spread and
     * interpolated across the ends.
     */
    ImmersedCoupling(const Triangulation<3>      &triangulation,
                     const Mapping<3>            &mapping,
                     const DoFHandler<3>         &velocity_dof_handler,
                     const std::optional<double> &period = std::nullopt);

    /**
     * Place the points, at the start and after every move (the same list on
     * every rank). Every rank finds every point's cell (the mesh is shared,
     * the search starts from the point's previous cell) and keeps the points
     * in its own cells, so points pass between cells and ranks without
     * communication. Throws std::runtime_error naming the first point that
     * lies outside the fluid domain, on every rank alike.
     */
    void
    place(const std::vector<Point<3>> &points);

    /**
     * Add f_J = Σ_I F_I · φ_J(x_I) to @p load (the layout of
     * FluidProblem::initialize_velocity_vector(), its ghost entries zero;
     * compressed here), condensed with @p constraints.
     */
    void
    spread(const std::vector<Tensor<1, 3>> &forces,
           const AffineConstraints<double> &constraints,
           VelocityVector                  &load) const;

    /**
     * v_I = Σ_J v_J φ_J(x_I) at every point, from @p velocity (ghosted);
     * the same result on every rank.
     */
    std::vector<Tensor<1, 3>>
    interpolate(const VelocityVector &velocity) const;

    unsigned int
    n_points() const;

    /**
     * The fluid mesh size the membranes see: the largest edge length
     * (shortest vertex distance) of the fluid cells that hold points [µm].
     */
    double
    mesh_size_at_points() const;

    const Particles::ParticleHandler<3> &
    get_particle_handler() const;

  private:
    /**
     * Call @p f(dofs, particles) for every cell of this rank that holds
     * particles, with the DoF indices of the cell and the range of its
     * particles.
     */
    template <typename CellFunction>
    void
    for_each_particle_cell(const CellFunction &f) const;

    const Triangulation<3>       &triangulation;
    const DoFHandler<3>          &dof_handler;
    const std::optional<double>   period;
    const GridTools::Cache<3>     cache;
    Particles::ParticleHandler<3> particles;
    /// Per point, the fluid cell it was last found in: where the next search
    /// starts.
    std::vector<Triangulation<3>::active_cell_iterator> cell_hints;
    unsigned int                                        n_membrane_points = 0;
    /// (local DoF k, velocity component c) of every velocity shape function.
    std::vector<std::pair<unsigned int, unsigned int>> velocity_shape_functions;
    /**
     * The velocity shape functions' values φ_k(x_I) at every particle of
     * this rank, in the order for_each_particle_cell() visits them: taken
     * in place(), used by spread() and interpolate().
     */
    std::vector<double> shape_values;
  };
} // namespace rbc_ifem

#endif
