#include <rbc_ifem/base/input_error.h>
#include <rbc_ifem/base/parameter_tools.h>
#include <rbc_ifem/geometry/parameters.h>

#include <deal.II/base/patterns.h>

#include <filesystem>
#include <fstream>

namespace rbc_ifem
{
  void
  GeometryParameters::add_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Geometry");
    add_parameter(prm,
                  "Capillary radius",
                  capillary_radius,
                  "Radius of the capillary lumen [µm]. The segment is the "
                  "cylinder of this radius along the x axis.",
                  GreaterThan());
    add_parameter(prm,
                  "Capillary length",
                  capillary_length,
                  "Length of the capillary segment, from x = 0 to "
                  "x = length [µm]. 20 µm holds 7 cells of 7.5 µm, as in "
                  "the paper.",
                  GreaterThan());
    add_parameter(prm,
                  "Wall thickness",
                  wall_thickness,
                  "Thickness of the vessel wall (tissue) around the "
                  "lumen [µm].",
                  GreaterThan());
    add_parameter(prm,
                  "Gas layer thickness",
                  gas_layer_thickness,
                  "Thickness of the alveolar gas layer outside the wall "
                  "[µm]; P = P_A holds on its outer surface.",
                  GreaterThan());
    add_parameter(prm,
                  "Periodic",
                  periodic,
                  "true: the segment repeats along x, a train of cells in an "
                  "endless capillary. The plasma is periodic (driven by the "
                  "constant pressure gradient 8μū/R² that carries the mean "
                  "speed ū = Fluid/Inlet mean speed through the empty "
                  "capillary; no inflow profile), so is the CO partial "
                  "pressure, a cell leaving at x = L re-enters at x = 0, and "
                  "cells interact across the ends. false: an inlet with "
                  "Poiseuille inflow at x = 0, a traction-free outlet at "
                  "x = L, no CO flux through the end faces.");
    prm.leave_subsection();
  }

  std::optional<double>
  GeometryParameters::period() const
  {
    return periodic ? std::optional<double>(capillary_length) : std::nullopt;
  }

  void
  MeshParameters::add_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Mesh");
    add_parameter(prm,
                  "Fluid global refinements",
                  fluid_global_refinements,
                  "Global refinements of the coarse lumen mesh (fluid).",
                  Patterns::Integer(0, 6));
    add_parameter(prm,
                  "Fluid band refinements",
                  fluid_band_refinements,
                  "Further refinements of the fluid mesh in a band around "
                  "the cell membranes (see Band width).",
                  Patterns::Integer(0, 4));
    add_parameter(prm,
                  "Diffusion global refinements",
                  diffusion_global_refinements,
                  "Global refinements of the coarse lumen + wall + gas "
                  "mesh (CO diffusion).",
                  Patterns::Integer(0, 6));
    add_parameter(prm,
                  "Diffusion band refinements",
                  diffusion_band_refinements,
                  "Further refinements of the diffusion mesh in a band "
                  "around the cell membranes. Cut cells (Diffusion/Method, "
                  "the default): 1, with degree 2, is the default mesh (its "
                  "error: doc/diffusion.md, Mesh convergence). Lagrange "
                  "multiplier: the mesh there must be about as fine as the "
                  "membranes or finer; CO fluxes are smoothest with "
                  "membrane cells about twice the size of the mesh cells "
                  "(with 1 global refinement: band refinements = "
                  "Cells/Surface refinements).",
                  Patterns::Integer(0, 5));
    add_parameter(prm,
                  "Diffusion gap refinements",
                  diffusion_gap_refinements,
                  "Diffusion/Method = cut cell only: where two membranes "
                  "pass through one cell of the diffusion mesh (a gap "
                  "narrower than the mesh), or a cell reaches across a part "
                  "of one red cell thinner than the mesh (the dimple, a "
                  "fold), that cell and its neighbours are refined once "
                  "more, up to this many times; if two membranes still "
                  "share a cell the run stops with an error, a thin part is "
                  "left as resolved as it is. 0 turns the local refinement "
                  "off.",
                  Patterns::Integer(0, 6));
    add_parameter(prm,
                  "Band width",
                  band_width,
                  "Half-width of the band around the membranes that band "
                  "refinement acts on [µm]: a mesh cell is refined if it "
                  "comes closer than this to a membrane.",
                  Patterns::Double(0.));
    prm.leave_subsection();
  }

  const SelectionNames<ReferenceShape> &
  reference_shape_names()
  {
    static const SelectionNames<ReferenceShape> names{
      {ReferenceShape::biconcave, "biconcave"},
      {ReferenceShape::sphere, "sphere"}};
    return names;
  }

  void
  CellParameters::add_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Cells");
    add_selection(prm,
                  "Shape",
                  shape,
                  reference_shape_names(),
                  "Reference shape of every cell: biconcave, the Evans-Fung "
                  "red cell; sphere, a spherical capsule of the same "
                  "Diameter (the validation runs, doc/validation.md).");
    add_parameter(prm,
                  "Diameter",
                  diameter,
                  "Diameter 2R of the Evans-Fung biconcave reference "
                  "shape [µm]; its thickness scales with it. Must be "
                  "smaller than the capillary diameter.",
                  GreaterThan());
    add_parameter(prm,
                  "Surface refinements",
                  surface_refinements,
                  "Global refinements of each membrane surface mesh; the "
                  "coarse mesh has 6 quadrilaterals, each refinement "
                  "multiplies that by 4.",
                  Patterns::Integer(0, 7));
    add_parameter(prm,
                  "Axis",
                  axis,
                  "Direction of every cell's symmetry axis (x, y, z; "
                  "normalised). The default 1,0,0 is the capillary axis: "
                  "the cells face the flow, as in the paper.",
                  Patterns::List(Patterns::Double(), 3, 3, ","));
    // Every direction is kept as a unit vector; validate() rejects zero.
    prm.add_action("Axis", [this](const std::string &) {
      if (axis.norm() > 0.)
        axis /= axis.norm();
    });
    prm.leave_subsection();
  }

  void
  CellParameters::validate() const
  {
    if (axis.norm() == 0.)
      throw InputError("Cells/Axis",
                       Patterns::Tools::to_string(axis),
                       "a direction must be nonzero.");
  }

  const SelectionNames<LayoutKind> &
  layout_kind_names()
  {
    static const SelectionNames<LayoutKind> names{
      {LayoutKind::uniform, "uniform"},
      {LayoutKind::random, "random"},
      {LayoutKind::clustered, "clustered"},
      {LayoutKind::file, "file"}};
    return names;
  }

  void
  LayoutParameters::add_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Layout");
    add_selection(prm,
                  "Kind",
                  kind,
                  layout_kind_names(),
                  "uniform: equal spacing over the segment; random: "
                  "positions drawn from Seed, uniformly over all "
                  "non-overlapping arrangements; clustered: cells stacked "
                  "at Minimum gap, the group placed by Cluster position; "
                  "file: the cells of File.");
    add_parameter(prm,
                  "Number of cells",
                  n_cells,
                  "Number of red cells N in the segment, for one layout. At "
                  "most floor(length / (cell length + Minimum gap)) fit. Not "
                  "used with Kind = file, whose rows are the cells, nor by "
                  "the studies, which take the list Layout study/Numbers of "
                  "cells.",
                  Patterns::Integer(0));
    add_parameter(prm,
                  "Seed",
                  seed,
                  "Seed of the random layout; the same seed gives the "
                  "same layout on any number of MPI ranks.",
                  Patterns::Integer(0));
    add_parameter(prm,
                  "Minimum gap",
                  minimum_gap,
                  "Smallest distance between the surfaces of two "
                  "neighbouring cells [µm]; cells keep half of it from the "
                  "segment's end faces.",
                  GreaterThan());
    add_parameter(prm,
                  "Cluster position",
                  cluster_position,
                  "Centre of the clustered group as a fraction of the "
                  "capillary length (0.5: centred).",
                  Patterns::Double(0., 1.));
    add_parameter(prm,
                  "File",
                  file,
                  "Kind = file: a CSV file with the header "
                  "x,y,z,axis_x,axis_y,axis_z and one row per cell, its "
                  "centre [µm] and the direction of its symmetry axis (any "
                  "length; Cells/Axis is not used). The cells must keep "
                  "Minimum gap between them and half of it from the end "
                  "faces, and lie inside the lumen. The layouts experiments "
                  "write every layout they draw in this form "
                  "(layout_<kind>_<n>_<seed>.csv). A relative path is "
                  "taken from the folder of this parameter file (from the "
                  "working directory when given by --set); the run copies "
                  "the file into its Output directory and its "
                  "parameters.prm names the copy.",
                  Patterns::FileName());
    prm.leave_subsection();
  }

  void
  LayoutParameters::validate() const
  {
    if (kind == LayoutKind::file && file.empty())
      throw InputError("Layout/File",
                       "",
                       "Layout/Kind = file needs the CSV file of the cells.");
    if (kind == LayoutKind::file &&
        (!std::filesystem::is_regular_file(file) || !std::ifstream(file)))
      throw InputError(
        "Layout/File",
        file,
        "there is no readable file " +
          std::filesystem::absolute(file).lexically_normal().string() +
          ". A relative path in a parameter file is taken from that file's "
          "folder, one given by --set from the working directory.");
  }

  void
  LayoutStudyParameters::add_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Layout study");
    add_selection(prm,
                  "Kinds",
                  kinds,
                  layout_kind_names(),
                  "Experiments 'layouts' and 'flowing layouts': the layout "
                  "kinds to compare (not file: a file is one layout).");
    add_parameter(prm,
                  "Numbers of cells",
                  numbers_of_cells,
                  "Experiments 'layouts' and 'flowing layouts': the list of "
                  "the numbers of cells N to place in the segment, each in "
                  "every kind (these experiments do not use Layout/Number "
                  "of cells).",
                  Patterns::List(Patterns::Integer(1), 1));
    add_parameter(prm,
                  "Random seeds",
                  n_seeds,
                  "Experiments 'layouts' and 'flowing layouts': how many "
                  "random layouts to draw for each N (a count, not a "
                  "seed): with the seeds Layout/Seed, Layout/Seed + 1, ..., "
                  "Layout/Seed + Random seeds - 1; layouts.csv reports "
                  "their mean and spread.",
                  Patterns::Integer(1));
    prm.leave_subsection();
  }

  void
  LayoutStudyParameters::validate() const
  {
    for (const LayoutKind kind : kinds)
      if (kind == LayoutKind::file)
        throw InputError("Layout study/Kinds",
                         "file",
                         "the study places N cells of each kind; a layout "
                         "from a file is run by Experiment = diffusion or "
                         "flow with Layout/Kind = file.");
  }

  std::vector<std::vector<LayoutParameters>>
  LayoutStudyParameters::layouts(const LayoutParameters &layout) const
  {
    std::vector<std::vector<LayoutParameters>> study;
    for (const LayoutKind kind : kinds)
      for (const unsigned int n : numbers_of_cells)
        {
          study.emplace_back();
          const unsigned int n_samples =
            kind == LayoutKind::random ? n_seeds : 1;
          for (unsigned int sample = 0; sample < n_samples; ++sample)
            {
              LayoutParameters one = layout;
              one.kind             = kind;
              one.n_cells          = n;
              one.seed             = layout.seed + sample;
              study.back().push_back(one);
            }
        }
    return study;
  }
} // namespace rbc_ifem
