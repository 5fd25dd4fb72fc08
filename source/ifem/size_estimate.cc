#include <rbc_ifem/base/input_error.h>
#include <rbc_ifem/geometry/capillary_mesh.h>
#include <rbc_ifem/geometry/evans_fung.h>
#include <rbc_ifem/ifem/size_estimate.h>

#include <deal.II/grid/tria.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>

namespace rbc_ifem
{
  namespace
  {
    // Fitted to the peaks that benchmarks/size_estimate.sh measures (one
    // rank, fluid global refinements 1-3, diffusion band refinements 1-2,
    // 1 and 7 cells; doc/results/benchmarks/size_estimate.csv): what a rank
    // holds besides the meshes and the membranes, per estimated DoF of each
    // mesh on it, and per membrane point (all of them, as on one rank).
    constexpr double base_mb              = 200.;
    constexpr double kb_per_fluid_dof     = 1.6;
    constexpr double kb_per_diffusion_dof = 8.;
    constexpr double kb_per_point         = 5.;
    constexpr double fluid_dofs_per_cell  = 25.;

    /**
     * The cells of a mesh of @p n_coarse cells filling @p volume, refined
     * @p n_global times, then @p n_band times within @p band_width of
     * membranes of total @p area (see the class text).
     */
    double
    refined_cells(const double       n_coarse,
                  const double       volume,
                  const unsigned int n_global,
                  const double       area,
                  const double       band_width,
                  const unsigned int n_band)
    {
      double cells = n_coarse * std::pow(8., n_global);
      double h     = std::cbrt(volume / cells);
      for (unsigned int level = 0; level < n_band; ++level, h /= 2.)
        {
          const double in_band =
            std::min(area * 2. * (band_width + h) / (h * h * h),
                     volume / (h * h * h));
          cells += 7. * in_band;
        }
      return cells;
    }

    /// The cells of the diffusion mesh of @p parameters around membranes
    /// of total @p area: refined_cells() of its coarse mesh (the lumen, the
    /// wall and the gas layer).
    double
    diffusion_mesh_cells(const Parameters &parameters, const double area)
    {
      const GeometryParameters &geometry = parameters.geometry;
      Triangulation<3>          coarse;
      create_diffusion_mesh(coarse, geometry, 0);
      const double outer = geometry.capillary_radius + geometry.wall_thickness +
                           geometry.gas_layer_thickness;
      return refined_cells(coarse.n_active_cells(),
                           numbers::PI * outer * outer *
                             geometry.capillary_length,
                           parameters.mesh.diffusion_global_refinements,
                           area,
                           parameters.mesh.band_width,
                           parameters.mesh.diffusion_band_refinements);
    }

    /// MemAvailable of /proc/meminfo [MB]; infinite where it cannot be read.
    double
    available_mb()
    {
      std::ifstream meminfo("/proc/meminfo");
      std::string   name;
      double        kb = 0.;
      while (meminfo >> name >> kb)
        {
          if (name == "MemAvailable:")
            return kb / 1024.;
          meminfo.ignore(256, '\n');
        }
      return std::numeric_limits<double>::infinity();
    }

    /// The number of ranks of @p communicator on this rank's machine.
    unsigned int
    ranks_on_this_machine(const MPI_Comm communicator)
    {
      MPI_Comm machine;
      MPI_Comm_split_type(
        communicator, MPI_COMM_TYPE_SHARED, 0, MPI_INFO_NULL, &machine);
      const unsigned int n = Utilities::MPI::n_mpi_processes(machine);
      MPI_Comm_free(&machine);
      return n;
    }
  } // namespace

  SizeEstimate::SizeEstimate(const Parameters  &parameters,
                             const FlowDomain  &domain,
                             const unsigned int n_ranks)
  {
    const MeshParameters &mesh    = parameters.mesh;
    const unsigned int    n_cells = domain.placements.size();
    const double          area =
      n_cells * EvansFungShape::of(parameters.cells).exact_area();
    fluid_cells = refined_cells(domain.n_coarse_cells,
                                domain.volume,
                                domain.n_global_refinements,
                                area,
                                mesh.band_width,
                                mesh.fluid_band_refinements);
    fluid_dofs  = fluid_dofs_per_cell * fluid_cells;
    if (parameters.immersed.diffusion_interval > 0 && domain.wall_radius)
      {
        diffusion_cells = diffusion_mesh_cells(parameters, area);
        diffusion_dofs =
          std::pow(parameters.diffusion.degree, 3) * diffusion_cells;
      }
    // The cube's 6 faces, each split 4^s times, and their vertices.
    membrane_points =
      n_cells * (6. * std::pow(4., parameters.cells.surface_refinements) + 2.);
    memory_mb =
      base_mb + kb_per_point * membrane_points / 1024. +
      (kb_per_fluid_dof * fluid_dofs + kb_per_diffusion_dof * diffusion_dofs) /
        (1024. * n_ranks);
    name_largest_part(mesh, n_cells, n_ranks);
  }

  void
  SizeEstimate::name_largest_part(const MeshParameters &mesh,
                                  const unsigned int    n_cells,
                                  const unsigned int    n_ranks)
  {
    const double fluid     = kb_per_fluid_dof * fluid_dofs / n_ranks;
    const double diffusion = kb_per_diffusion_dof * diffusion_dofs / n_ranks;
    const double membranes = kb_per_point * membrane_points;
    if (membranes >= std::max(fluid, diffusion))
      {
        dominant_parameter = "Layout/Number of cells";
        dominant_value     = std::to_string(n_cells);
      }
    else if (fluid >= diffusion)
      {
        dominant_parameter = "Mesh/Fluid global refinements";
        dominant_value     = std::to_string(mesh.fluid_global_refinements);
      }
    else
      {
        dominant_parameter = "Mesh/Diffusion global refinements";
        dominant_value     = std::to_string(mesh.diffusion_global_refinements);
      }
  }

  std::string
  SizeEstimate::meshes() const
  {
    std::ostringstream out;
    out.precision(2);
    out << "fluid mesh about " << fluid_cells << " cells, " << fluid_dofs
        << " DoFs";
    if (diffusion_cells > 0.)
      out << "; diffusion mesh about " << diffusion_cells << " cells, "
          << diffusion_dofs << " DoFs";
    out << "; " << membrane_points << " membrane points";
    return out.str();
  }

  std::string
  SizeEstimate::text() const
  {
    std::ostringstream out;
    out.precision(3);
    out << "size estimate: " << meshes() << "; about " << memory_mb
        << " MB per rank";
    return out.str();
  }

  void
  SizeEstimate::check(const MPI_Comm communicator, const bool force) const
  {
    const double needed = memory_mb * ranks_on_this_machine(communicator);
    const double have   = available_mb();
    const bool   too_large =
      Utilities::MPI::max(needed > have ? 1 : 0, communicator) == 1;
    if (!too_large || force)
      return;
    std::ostringstream why;
    why.precision(3);
    why << "the run would need about " << needed << " MB on this machine ("
        << memory_mb << " MB per rank; " << meshes() << "), and it has " << have
        << " MB available. Lower the refinements, run on more machines, "
           "or give --force to run it anyway.";
    throw InputError(dominant_parameter, dominant_value, why.str());
  }
} // namespace rbc_ifem
