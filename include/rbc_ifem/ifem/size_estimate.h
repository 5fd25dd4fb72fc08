#ifndef rbc_ifem_ifem_size_estimate_h
#define rbc_ifem_ifem_size_estimate_h

#include <rbc_ifem/ifem/flow_domain.h>
#include <rbc_ifem/parameters.h>

#include <deal.II/base/mpi.h>

#include <string>

namespace rbc_ifem
{
  /**
   * What a flowing run will need, estimated from its parameters before any
   * mesh is built: the cells and DoFs of the fluid mesh and, with DM
   * solves, of the diffusion mesh, and the peak memory of a rank.
   *
   * A mesh's cells are its coarse cells refined globally, plus what the
   * band refinement adds: at each of its levels, the cells within Mesh/Band
   * width of a membrane (and at least a cell's width, on either side) split
   * into eight. The DoFs are 25 per fluid cell (Q2 velocity and Q1
   * pressure, interior count) and k³ per diffusion cell (FE_Q(k)); the
   * memory is a base plus a measured amount per DoF and per membrane point
   * (every membrane point, as one rank holds them: an upper bound on more
   * ranks, where a rank keeps the membranes of its own cells only; the
   * constants of size_estimate.cc,
   * from benchmarks/size_estimate.sh, which compares the estimate with what
   * runs build and use: doc/results/benchmarks/size_estimate.csv).
   */
  class SizeEstimate
  {
  public:
    /// The estimate for a run of @p parameters in @p domain on @p n_ranks.
    SizeEstimate(const Parameters  &parameters,
                 const FlowDomain  &domain,
                 const unsigned int n_ranks);

    /// "size estimate: fluid mesh about N cells, M DoFs; ...; about X MB
    /// per rank", for the start-up report.
    std::string
    text() const;

    /**
     * Throw InputError naming the global refinements of the larger mesh if
     * the ranks on one machine would need more memory together than it has
     * available (MemAvailable of /proc/meminfo), unless @p force.
     * Collective.
     */
    void
    check(const MPI_Comm communicator, const bool force) const;

    double fluid_cells     = 0.;
    double fluid_dofs      = 0.;
    double diffusion_cells = 0.; ///< 0 without DM solves
    double diffusion_dofs  = 0.;
    double membrane_points = 0.; ///< of all cells, held by every rank
    double memory_mb       = 0.; ///< the peak of one rank [MB]

  private:
    /// Set the parameter behind the largest part of the memory (the fluid
    /// mesh, the diffusion mesh or the membranes), to name in a refusal.
    void
    name_largest_part(const MeshParameters &mesh,
                      const unsigned int    n_cells,
                      const unsigned int    n_ranks);

    /// "fluid mesh about N cells, M DoFs; diffusion mesh ...".
    std::string
    meshes() const;

    /// The parameter whose value makes the run large, and its value.
    std::string dominant_parameter, dominant_value;
  };
} // namespace rbc_ifem

#endif
