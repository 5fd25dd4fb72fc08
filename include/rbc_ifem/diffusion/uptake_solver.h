#ifndef rbc_ifem_diffusion_uptake_solver_h
#define rbc_ifem_diffusion_uptake_solver_h

#include <rbc_ifem/diffusion/parameters.h>
#include <rbc_ifem/diffusion/uptake.h>
#include <rbc_ifem/geometry/membrane_surfaces.h>
#include <rbc_ifem/geometry/parameters.h>

#include <deal.II/base/mpi.h>
#include <deal.II/base/timer.h>

#include <functional>
#include <vector>

namespace rbc_ifem
{
  using namespace dealii;

  class DiffusionSolver;

  /**
   * The DM building block: the CO uptake of a set of membranes in the
   * capillary, built once from its parameters and then asked for each set
   * of membranes (a layout's rigid cells, or the flowing cells at each DM
   * instant). A solve makes the uptake mesh around the membranes
   * (UptakeMesh: the capillary's diffusion mesh refined Mesh/Diffusion band
   * refinements times within Mesh/Band width of them, and where the cut
   * cells cannot resolve them), then solves by the method of
   * Diffusion/Method:
   * - cut cell: the CutCellGeometry of the membranes in it, built once and
   *   shared by CutCellDiffusion (DM) and, with Diffusion/Uptake =
   *   reaction, CutCellReaction (DL) on the same mesh;
   * - Lagrange multiplier: CODiffusion (DM).
   */
  class UptakeSolver
  {
  public:
    /**
     * The solver of @p diffusion in the capillary of @p geometry, on the
     * meshes of @p mesh, over the ranks of @p communicator; its sections
     * are timed in @p timer, which must outlive it.
     */
    UptakeSolver(const GeometryParameters  &geometry,
                 const MeshParameters      &mesh,
                 const DiffusionParameters &diffusion,
                 const MPI_Comm             communicator,
                 TimerOutput               &timer);

    /**
     * What solve() does before it assembles: throws InputError for what it
     * would reject (a membrane outside the mesh or in the wall, a
     * diffusion mesh too coarse for the membranes, two membranes closer
     * than the mesh resolves), so that a run can refuse its input before it
     * writes anything.
     */
    void
    check(const MembraneSurfaces &surfaces) const;

    /**
     * The CO uptake of @p surfaces; then @p write_fields, if given, writes
     * what the caller wants of the solve (with Diffusion/Uptake = reaction
     * the reaction's, DL's). Throws SolverFailure if a solve fails.
     */
    Uptake
    solve(const MembraneSurfaces                             &surfaces,
          const std::function<void(const DiffusionSolver &)> &write_fields = {})
      const;

    /**
     * What solve() gives with Diffusion/Uptake = reaction, for each
     * binding rate k of @p rates [s⁻¹ Torr⁻¹, DiffusionParameters::
     * reaction_rate()] in turn, on one uptake mesh: the mesh, its geometry
     * and DM are computed once. Element i has DL for rates[i] (@p rates not
     * empty), and as its seconds the wall time since element i − 1
     * (element 0: since the start, the mesh and DM included). Needs
     * Diffusion/Method = cut cell (InputError otherwise).
     */
    std::vector<Uptake>
    solve_for_rates(const MembraneSurfaces    &surfaces,
                    const std::vector<double> &rates) const;

  private:
    /**
     * The sink's solve on the uptake mesh, then one reaction solve per
     * rate of @p rates (with the mesh the reaction needs if @p rates is not
     * empty); each Uptake's seconds the wall time since the one before (the
     * first's since the start); @p write_fields is given the last solve.
     */
    std::vector<Uptake>
    solve_sink_and_rates(
      const MembraneSurfaces                             &surfaces,
      const std::vector<double>                          &rates,
      const std::function<void(const DiffusionSolver &)> &write_fields) const;

    const GeometryParameters  geometry;
    const MeshParameters      mesh;
    const DiffusionParameters diffusion;
    const MPI_Comm            communicator;
    TimerOutput              &timer;
  };
} // namespace rbc_ifem

#endif
