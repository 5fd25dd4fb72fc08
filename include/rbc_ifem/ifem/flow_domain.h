#ifndef rbc_ifem_flow_domain_h
#define rbc_ifem_flow_domain_h

#include <rbc_ifem/fluid/fluid_problem.h>
#include <rbc_ifem/geometry/cell_placement.h>
#include <rbc_ifem/parameters.h>

#include <deal.II/grid/tria.h>

#include <string>
#include <vector>

namespace rbc_ifem
{
  using namespace dealii;

  /**
   * The box of Experiment = shear, centred on the origin: @p box = (length,
   * height, width) along x, y, z, cut into cubes of edge @p cell_size and
   * refined @p n_global_refinements times. Boundary ids as in the capillary
   * (FluidBoundary): the ends x = ±L/2 are the inlet (1) and the outlet (2),
   * open; the faces y = ±H/2 and z = ±W/2 are the wall (0), where the shear
   * is imposed.
   */
  void
  create_shear_box_mesh(Triangulation<3>   &triangulation,
                        const Tensor<1, 3> &box,
                        const double        cell_size,
                        const unsigned int  n_global_refinements);

  /**
   * Where the immersed cells of an IFEMSimulation flow: the fluid mesh, what
   * drives the flow, where the cells start, and the numbers that describe
   * the run.
   */
  struct FlowDomain
  {
    enum class Kind
    {
      capillary, ///< Poiseuille flow in the capillary segment, cells of
                 ///< subsection Layout
      shear_box  ///< simple shear in a box, one capsule at its centre
    };

    Kind                       kind = Kind::capillary;
    FlowDrive                  drive;
    std::vector<CellPlacement> placements;
    double                     shear_rate = 0.; ///< γ̇ of the shear box [1/s]

    /// The capillary of subsection Geometry with the cells of subsection
    /// Layout.
    static FlowDomain
    capillary(const Parameters &parameters);

    /// The box of subsection Shear at shear rate γ̇, a capsule at the origin.
    static FlowDomain
    shear_box(const Parameters &parameters);

    /// The fluid mesh before the band refinement around the cells.
    void
    create_mesh(Triangulation<3> &triangulation,
                const Parameters &parameters) const;

    /// A velocity scale: the mean inflow speed ū, or γ̇ a in the box [µm/s].
    double
    velocity_scale(const Parameters &parameters) const;

    /// A length scale: the capillary diameter 2R, or the capsule radius a [µm].
    double
    length_scale(const Parameters &parameters) const;

    /// The name of the region the cells must stay in, for messages.
    std::string
    name() const;
  };
} // namespace rbc_ifem

#endif
