#ifndef rbc_ifem_experiments_uptake_experiment_h
#define rbc_ifem_experiments_uptake_experiment_h

#include <rbc_ifem/diffusion/uptake.h>
#include <rbc_ifem/experiments/experiment.h>
#include <rbc_ifem/geometry/cell_layout.h>
#include <rbc_ifem/geometry/cell_membranes.h>

#include <functional>
#include <string>

namespace rbc_ifem
{
  /**
   * The cells of one layout in the capillary: the CellLayout (InputError if
   * it is impossible) and the membranes on it, their meshes checked for
   * clearance (InputError if they cross each other or the wall).
   */
  struct PlacedCells
  {
    /// The layout of subsection Layout.
    PlacedCells(const Parameters  &parameters,
                const unsigned int surface_refinements);

    /// The cells of @p layout.
    PlacedCells(const Parameters  &parameters,
                const CellLayout  &layout,
                const unsigned int surface_refinements);

    /// The tube hematocrit of the membranes.
    double
    hematocrit() const;

    const CellLayout    layout;
    const CellMembranes membranes;
  };

  /**
   * What the CO uptake experiments (diffusion, layouts, mesh convergence)
   * share: each is a steady diffusion solve (CODiffusion, through
   * solve_uptake()) per layout on the capillary's diffusion mesh, refined in
   * a band around the membranes, and a progress line per solve.
   */
  class UptakeExperiment : public Experiment
  {
  protected:
    using Experiment::Experiment;

    /**
     * The uptake of @p cells on the diffusion mesh refined
     * @p band_refinements times around them; @p write_fields as for
     * solve_uptake().
     */
    Uptake
    solve(const PlacedCells                              &cells,
          const unsigned int                              band_refinements,
          const std::function<void(const CODiffusion &)> &write_fields = {});

    /// The progress line of one solve.
    void
    report(const std::string &what, const Uptake &uptake);
  };
} // namespace rbc_ifem

#endif
