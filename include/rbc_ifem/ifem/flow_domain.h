#ifndef rbc_ifem_ifem_flow_domain_h
#define rbc_ifem_ifem_flow_domain_h

#include <rbc_ifem/fluid/fluid_problem.h>
#include <rbc_ifem/geometry/cell_placement.h>
#include <rbc_ifem/parameters.h>

#include <deal.II/grid/tria.h>

#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace rbc_ifem
{
  using namespace dealii;

  /**
   * Where the immersed cells of an IFEMSimulation flow: the fluid mesh, what
   * drives the flow, where the cells start, and the scales that describe
   * the run. Everything the time loop needs to know of the domain is here,
   * so the loop is the same in every domain.
   */
  struct FlowDomain
  {
    /// The region the cells must stay in, for messages ("the capillary").
    std::string name;
    FlowDrive   drive;
    /// Where the cells start.
    std::vector<CellPlacement> placements;
    /// Create the coarse fluid mesh (boundary ids, manifolds), which the run
    /// refines n_global_refinements times and then around the cells.
    std::function<void(Triangulation<3> &)> create_mesh;
    /// The cells of create_mesh()'s coarse mesh and the volume they fill
    /// [µm³]: the size estimate's start (SizeEstimate), known before any
    /// mesh is built.
    unsigned int n_coarse_cells       = 0;
    unsigned int n_global_refinements = 0;
    double       volume               = 0.;
    /// The radius of the cylindrical wall about the x axis that the cells
    /// must stay inside (the capillary's); none for the shear box, whose
    /// walls the cells never reach.
    std::optional<double> wall_radius;
    /// The period along x of a periodic segment (Geometry/Periodic): cells
    /// that leave at one end re-enter at the other.
    std::optional<double> period;

    /// A velocity and a length scale for the Reynolds and capillary
    /// numbers, with their symbols for the log.
    double      velocity_scale = 0.; ///< [µm/s]
    std::string velocity_symbol;
    double      length_scale = 0.; ///< [µm]
    std::string length_symbol;

    /**
     * The capillary of subsection Geometry with the cells of subsection
     * Layout (CellLayout: throws InputError if they do not fit), Poiseuille
     * inflow of mean speed ū; or, with Geometry/Periodic, the periodic
     * segment driven by the pressure gradient of that mean speed.
     */
    static FlowDomain
    capillary(const Parameters &parameters);

    /**
     * The box of size @p box = (length, height, width) [µm] in simple shear
     * of rate @p shear_rate [1/s], one capsule of subsection Cells at the
     * origin; its coarse cells have the capsule's diameter as edge, refined
     * Mesh/Fluid global refinements times.
     */
    static FlowDomain
    shear_box(const Tensor<1, 3> &box,
              const double        shear_rate,
              const Parameters   &parameters);
  };
} // namespace rbc_ifem

#endif
