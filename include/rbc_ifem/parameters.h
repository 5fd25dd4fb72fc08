#ifndef rbc_ifem_parameters_h
#define rbc_ifem_parameters_h

#include <rbc_ifem/base/input_files.h>
#include <rbc_ifem/coupling/parameters.h>
#include <rbc_ifem/diffusion/parameters.h>
#include <rbc_ifem/fluid/parameters.h>
#include <rbc_ifem/geometry/parameters.h>
#include <rbc_ifem/ifem/parameters.h>
#include <rbc_ifem/membrane/parameters.h>

#include <deal.II/base/parameter_handler.h>

#include <string>
#include <vector>

namespace rbc_ifem
{
  using namespace dealii;

  /**
   * The parameters of the model one run solves, gathered from the structs
   * of each concern (each beside its code: geometry/parameters.h, ...).
   * Units (doc/design.md, "Units"): length µm, time s, force pN. The names of
   * the parameters listed in doc/design.md, "The public interface", never
   * change. An experiment's own subsection (Shear, Stretching, ...) belongs
   * to the experiment (experiments/), and RunParameters reads them all.
   */
  struct Parameters
  {
    std::string           output_directory = "output/run";
    GeometryParameters    geometry;
    MeshParameters        mesh;
    CellParameters        cells;
    LayoutParameters      layout;
    LayoutStudyParameters layout_study;
    FluidParameters       fluid;
    TimeParameters        time;
    MembraneParameters    membrane;
    ImmersedParameters    immersed;
    InteractionParameters interactions;
    DiffusionParameters   diffusion;

    /**
     * Declare Output directory and every subsection in @p prm, with the
     * members' values as defaults, and bind the members to them: parsing a
     * file into @p prm fills this object. It must outlive the parsing.
     */
    void
    add_parameters(ParameterHandler &prm);

    /**
     * Throw InputError, naming the parameter and the value, if a value is
     * allowed by its pattern but impossible (a zero length, a law that
     * cannot have the moduli, an output directory that is a file, ...).
     */
    void
    validate() const;

    /**
     * The files the run reads that parameters name: Layout/File when
     * Layout/Kind = file. A run copies them into its output directory.
     */
    std::vector<InputFile>
    input_files() const;
  };
} // namespace rbc_ifem

#endif
