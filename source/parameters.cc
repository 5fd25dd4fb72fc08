#include <rbc_ifem/input_error.h>
#include <rbc_ifem/parameters.h>

#include <deal.II/base/exceptions.h>
#include <deal.II/base/utilities.h>

#include <filesystem>
#include <fstream>
#include <sstream>

namespace rbc_ifem
{
  InputError::InputError(const std::string &message)
    : std::runtime_error(message)
  {}

  InputError::InputError(const std::string &parameter,
                         const std::string &value,
                         const std::string &allowed)
    : std::runtime_error("parameter '" + parameter + "' = '" + value +
                         "' is not allowed: " + allowed)
  {}

  namespace
  {
    std::string
    to_string(const double value)
    {
      std::ostringstream s;
      s << value;
      return s.str();
    }

    /// Throw unless @p value > 0; thicknesses and lengths of zero make no mesh.
    void
    require_positive(const std::string &name, const double value)
    {
      if (!(value > 0.))
        throw InputError(name, to_string(value), "it must be > 0 µm.");
    }
  } // namespace

  void
  GeometryParameters::declare(ParameterHandler &prm)
  {
    prm.enter_subsection("Geometry");
    prm.declare_entry("Capillary radius",
                      "5",
                      Patterns::Double(0.),
                      "Radius of the capillary lumen [µm]. The segment is the "
                      "cylinder of this radius along the x axis.");
    prm.declare_entry("Capillary length",
                      "20",
                      Patterns::Double(0.),
                      "Length of the capillary segment, from x = 0 to "
                      "x = length [µm]. 20 µm holds 7 cells of 7.5 µm, as in "
                      "the paper.");
    prm.declare_entry("Wall thickness",
                      "1",
                      Patterns::Double(0.),
                      "Thickness of the vessel wall (tissue) around the "
                      "lumen [µm].");
    prm.declare_entry("Gas layer thickness",
                      "5",
                      Patterns::Double(0.),
                      "Thickness of the alveolar gas layer outside the wall "
                      "[µm]; P = P_A holds on its outer surface.");
    prm.leave_subsection();
  }

  void
  GeometryParameters::parse(ParameterHandler &prm)
  {
    prm.enter_subsection("Geometry");
    capillary_radius    = prm.get_double("Capillary radius");
    capillary_length    = prm.get_double("Capillary length");
    wall_thickness      = prm.get_double("Wall thickness");
    gas_layer_thickness = prm.get_double("Gas layer thickness");
    prm.leave_subsection();
  }

  void
  GeometryParameters::validate() const
  {
    require_positive("Geometry/Capillary radius", capillary_radius);
    require_positive("Geometry/Capillary length", capillary_length);
    require_positive("Geometry/Wall thickness", wall_thickness);
    require_positive("Geometry/Gas layer thickness", gas_layer_thickness);
  }

  void
  MeshParameters::declare(ParameterHandler &prm)
  {
    prm.enter_subsection("Mesh");
    prm.declare_entry("Fluid global refinements",
                      "1",
                      Patterns::Integer(0, 6),
                      "Global refinements of the coarse lumen mesh (fluid).");
    prm.declare_entry("Fluid band refinements",
                      "1",
                      Patterns::Integer(0, 4),
                      "Further refinements of the fluid mesh in a band around "
                      "the cell membranes (see Band width).");
    prm.declare_entry("Diffusion global refinements",
                      "1",
                      Patterns::Integer(0, 6),
                      "Global refinements of the coarse lumen + wall + gas "
                      "mesh (CO diffusion).");
    prm.declare_entry("Diffusion band refinements",
                      "1",
                      Patterns::Integer(0, 4),
                      "Further refinements of the diffusion mesh in a band "
                      "around the cell membranes.");
    prm.declare_entry("Band width",
                      "0.5",
                      Patterns::Double(0.),
                      "Half-width of the band around the membranes that band "
                      "refinement acts on [µm]: a mesh cell is refined if it "
                      "comes closer than this to a membrane.");
    prm.leave_subsection();
  }

  void
  MeshParameters::parse(ParameterHandler &prm)
  {
    prm.enter_subsection("Mesh");
    fluid_global_refinements     = prm.get_integer("Fluid global refinements");
    fluid_band_refinements       = prm.get_integer("Fluid band refinements");
    diffusion_global_refinements = prm.get_integer("Diffusion global refinements");
    diffusion_band_refinements   = prm.get_integer("Diffusion band refinements");
    band_width                   = prm.get_double("Band width");
    prm.leave_subsection();
  }

  void
  CellParameters::declare(ParameterHandler &prm)
  {
    prm.enter_subsection("Cells");
    prm.declare_entry("Diameter",
                      "7.5",
                      Patterns::Double(0.),
                      "Diameter 2R of the Evans-Fung biconcave reference "
                      "shape [µm]; its thickness scales with it. Must be "
                      "smaller than the capillary diameter.");
    prm.declare_entry("Surface refinements",
                      "3",
                      Patterns::Integer(0, 7),
                      "Global refinements of each membrane surface mesh; the "
                      "coarse mesh has 6 quadrilaterals, each refinement "
                      "multiplies that by 4.");
    prm.declare_entry("Axis",
                      "1, 0, 0",
                      Patterns::List(Patterns::Double(), 3, 3, ","),
                      "Direction of every cell's symmetry axis (x, y, z; "
                      "normalised). The default 1,0,0 is the capillary axis: "
                      "the cells face the flow, as in the paper.");
    prm.leave_subsection();
  }

  void
  CellParameters::parse(ParameterHandler &prm)
  {
    prm.enter_subsection("Cells");
    diameter            = prm.get_double("Diameter");
    surface_refinements = prm.get_integer("Surface refinements");
    const std::string axis_text = prm.get("Axis");
    const auto        components =
      Utilities::string_to_double(Utilities::split_string_list(axis_text));
    for (unsigned int d = 0; d < 3; ++d)
      axis[d] = components[d];
    if (axis.norm() == 0.)
      throw InputError("Cells/Axis", axis_text, "a direction must be nonzero.");
    axis /= axis.norm();
    prm.leave_subsection();
  }

  void
  CellParameters::validate(const GeometryParameters &geometry) const
  {
    require_positive("Cells/Diameter", diameter);
    if (diameter >= 2. * geometry.capillary_radius)
      throw InputError("Cells/Diameter",
                       to_string(diameter),
                       "the cell must be smaller than the capillary diameter "
                       "2 x Geometry/Capillary radius = " +
                         to_string(2. * geometry.capillary_radius) + " µm.");
  }

  void
  LayoutParameters::declare(ParameterHandler &prm)
  {
    prm.enter_subsection("Layout");
    prm.declare_entry("Kind",
                      "uniform",
                      Patterns::Selection("uniform|random|clustered"),
                      "uniform: equal spacing over the segment; random: "
                      "positions drawn from Seed, uniformly over all "
                      "non-overlapping arrangements; clustered: cells stacked "
                      "at Minimum gap, the group placed by Cluster position.");
    prm.declare_entry("Number of cells",
                      "4",
                      Patterns::Integer(0),
                      "Number of red cells in the segment. At most "
                      "floor(length / (cell length + Minimum gap)) fit.");
    prm.declare_entry("Seed",
                      "1",
                      Patterns::Integer(0),
                      "Seed of the random layout; the same seed gives the "
                      "same layout on any number of MPI ranks.");
    prm.declare_entry("Minimum gap",
                      "0.2",
                      Patterns::Double(0.),
                      "Smallest distance between the surfaces of two "
                      "neighbouring cells [µm]; cells keep half of it from the "
                      "segment's end faces.");
    prm.declare_entry("Cluster position",
                      "0.5",
                      Patterns::Double(0., 1.),
                      "Centre of the clustered group as a fraction of the "
                      "capillary length (0.5: centred).");
    prm.leave_subsection();
  }

  void
  LayoutParameters::parse(ParameterHandler &prm)
  {
    prm.enter_subsection("Layout");
    kind             = prm.get("Kind");
    n_cells          = prm.get_integer("Number of cells");
    seed             = prm.get_integer("Seed");
    minimum_gap      = prm.get_double("Minimum gap");
    cluster_position = prm.get_double("Cluster position");
    prm.leave_subsection();
    if (!(minimum_gap > 0.))
      throw InputError("Layout/Minimum gap",
                       to_string(minimum_gap),
                       "it must be > 0 µm: cells must not touch.");
  }

  void
  Parameters::declare(ParameterHandler &prm)
  {
    prm.declare_entry("Experiment",
                      "geometry",
                      Patterns::Selection("geometry"),
                      "What to run. geometry: build the fluid and diffusion "
                      "meshes and the cell layout, and write them out.");
    prm.declare_entry("Output directory",
                      "output/run",
                      Patterns::DirectoryName(),
                      "Where the run writes its files; created if needed.");
    GeometryParameters::declare(prm);
    MeshParameters::declare(prm);
    CellParameters::declare(prm);
    LayoutParameters::declare(prm);
  }

  void
  Parameters::parse(ParameterHandler &prm)
  {
    experiment       = prm.get("Experiment");
    output_directory = prm.get("Output directory");
    if (output_directory.empty() ||
        (std::filesystem::exists(output_directory) &&
         !std::filesystem::is_directory(output_directory)))
      throw InputError("Output directory",
                       output_directory,
                       "it must name a directory, new or existing, not a file.");
    geometry.parse(prm);
    mesh.parse(prm);
    cells.parse(prm);
    layout.parse(prm);
    geometry.validate();
    cells.validate(geometry);
  }

  void
  read_parameters(const std::string &filename,
                  ParameterHandler & prm,
                  Parameters &       parameters)
  {
    if (!std::filesystem::is_regular_file(filename) ||
        !std::ifstream(filename))
      throw InputError("cannot read the parameter file '" + filename +
                       "': it does not exist or is not a readable file.");

    Parameters::declare(prm);
    try
      {
        prm.parse_input(filename);
      }
    catch (const ExceptionBase &e)
      {
        // deal.II's message names the line, the entry, the value and the
        // pattern; drop the backtrace and point to the list of names.
        std::ostringstream message;
        e.print_info(message);
        throw InputError("in parameter file '" + filename + "':\n" +
                         message.str() +
                         "\nRun 'rbc-ifem --print-parameters' for every "
                         "parameter, its allowed values and its default.");
      }
    parameters.parse(prm);
  }
} // namespace rbc_ifem
