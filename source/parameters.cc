#include <rbc_ifem/base/input_error.h>
#include <rbc_ifem/base/parameter_tools.h>
#include <rbc_ifem/parameters.h>

#include <filesystem>

namespace rbc_ifem
{
  void
  Parameters::add_parameters(ParameterHandler &prm)
  {
    add_parameter(prm,
                  "Output directory",
                  output_directory,
                  "Where the run writes its files; created if needed.",
                  Patterns::DirectoryName());
    geometry.add_parameters(prm);
    mesh.add_parameters(prm);
    cells.add_parameters(prm);
    layout.add_parameters(prm);
    layout_study.add_parameters(prm);
    fluid.add_parameters(prm);
    time.add_parameters(prm);
    membrane.add_parameters(prm);
    immersed.add_parameters(prm);
    interactions.add_parameters(prm);
    diffusion.add_parameters(prm);
  }

  void
  Parameters::validate() const
  {
    if (output_directory.empty() ||
        (std::filesystem::exists(output_directory) &&
         !std::filesystem::is_directory(output_directory)))
      throw InputError(
        "Output directory",
        output_directory,
        "it must name a directory, new or existing, not a file.");
    cells.validate();
    layout.validate();
    layout_study.validate();
    membrane.validate();
    immersed.validate();
    interactions.validate(cells.diameter,
                          geometry.capillary_radius,
                          geometry.capillary_length);
    diffusion.validate();
  }

  std::vector<InputFile>
  Parameters::input_files() const
  {
    if (layout.kind == LayoutKind::file)
      return {{"Layout/File", layout.file}};
    return {};
  }
} // namespace rbc_ifem
