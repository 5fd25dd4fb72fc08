#include <rbc_ifem/base/input_error.h>
#include <rbc_ifem/geometry/capillary_mesh.h>
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

    /// Throw unless @p value > 0 (in @p unit, for the message): thicknesses
    /// and lengths of zero make no mesh, rates and strains of zero no run.
    void
    require_positive(const std::string &name,
                     const double       value,
                     const std::string &unit = " µm")
    {
      if (!(value > 0.))
        throw InputError(name, to_string(value), "it must be > 0" + unit + ".");
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
                      "3",
                      Patterns::Integer(0, 5),
                      "Further refinements of the diffusion mesh in a band "
                      "around the cell membranes. The mesh there must be about "
                      "as fine as the membranes or finer; CO fluxes are "
                      "smoothest with membrane cells about twice the size of "
                      "the mesh cells (with 1 global refinement: band "
                      "refinements = Cells/Surface refinements).");
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
    fluid_global_refinements = prm.get_integer("Fluid global refinements");
    fluid_band_refinements   = prm.get_integer("Fluid band refinements");
    diffusion_global_refinements =
      prm.get_integer("Diffusion global refinements");
    diffusion_band_refinements = prm.get_integer("Diffusion band refinements");
    band_width                 = prm.get_double("Band width");
    prm.leave_subsection();
  }

  void
  CellParameters::declare(ParameterHandler &prm)
  {
    prm.enter_subsection("Cells");
    prm.declare_entry(
      "Shape",
      "biconcave",
      Patterns::Selection("biconcave|sphere"),
      "Reference shape of every cell: biconcave, the Evans-Fung "
      "red cell; sphere, a spherical capsule of the same "
      "Diameter (the validation runs, doc/validation.md).");
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
    shape                       = prm.get("Shape");
    diameter                    = prm.get_double("Diameter");
    surface_refinements         = prm.get_integer("Surface refinements");
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
  FluidParameters::declare(ParameterHandler &prm)
  {
    prm.enter_subsection("Fluid");
    prm.declare_entry("Model",
                      "Stokes",
                      Patterns::Selection("Stokes|Navier-Stokes"),
                      "Stokes: unsteady Stokes, the fast path (the capillary "
                      "Reynolds number is ~1e-5); Navier-Stokes: with the "
                      "convective term, Newton-Raphson in every time step.");
    prm.declare_entry("Viscosity",
                      "1.2e-3",
                      Patterns::Double(0.),
                      "Dynamic viscosity μ of plasma (and of the cytoplasm: "
                      "viscosity ratio 1) [pN s/µm²]; 1.2e-3 is 1.2 mPa s.");
    prm.declare_entry("Density",
                      "1e-9",
                      Patterns::Double(0.),
                      "Density ρ [mg/µm³]; 1e-9 is 1000 kg/m³.");
    prm.declare_entry("Inlet mean speed",
                      "500",
                      Patterns::Double(),
                      "Mean speed ū of the Poiseuille inflow at x = 0, "
                      "u(r) = 2ū(1 - r²/R²) [µm/s]; capillary red cells move "
                      "at 300-700 µm/s.");
    prm.declare_entry("Frame velocity",
                      "0",
                      Patterns::Double(),
                      "Velocity U_frame of the computational frame along x "
                      "[µm/s]: walls and inflow move at -U_frame in it. 0 is "
                      "the laboratory frame.");
    prm.declare_entry("Linear solver tolerance",
                      "1e-6",
                      Patterns::Double(0.),
                      "FGMRES stops when the residual is this fraction of the "
                      "largest residual of the run (the problem's scale); "
                      "1e-6 leaves the solution 1e-6 from exact, far below "
                      "the discretisation error.");
    prm.declare_entry("Max linear iterations",
                      "500",
                      Patterns::Integer(1),
                      "FGMRES gives up (and the run stops) after this many "
                      "iterations.");
    prm.declare_entry("Newton tolerance",
                      "1e-8",
                      Patterns::Double(0.),
                      "Navier-Stokes: Newton stops when the residual has "
                      "fallen by this factor from its first value in the "
                      "step.");
    prm.declare_entry("Max Newton iterations",
                      "20",
                      Patterns::Integer(1),
                      "Navier-Stokes: the run stops if Newton has not "
                      "converged after this many iterations.");
    prm.leave_subsection();
  }

  void
  FluidParameters::parse(ParameterHandler &prm)
  {
    prm.enter_subsection("Fluid");
    model                 = prm.get("Model");
    viscosity             = prm.get_double("Viscosity");
    density               = prm.get_double("Density");
    inlet_mean_speed      = prm.get_double("Inlet mean speed");
    frame_velocity        = prm.get_double("Frame velocity");
    linear_tolerance      = prm.get_double("Linear solver tolerance");
    max_linear_iterations = prm.get_integer("Max linear iterations");
    newton_tolerance      = prm.get_double("Newton tolerance");
    max_newton_iterations = prm.get_integer("Max Newton iterations");
    prm.leave_subsection();
    if (!(viscosity > 0.))
      throw InputError("Fluid/Viscosity",
                       to_string(viscosity),
                       "it must be > 0 pN s/µm².");
  }

  void
  TimeParameters::declare(ParameterHandler &prm)
  {
    prm.enter_subsection("Time");
    prm.declare_entry("Time step",
                      "1e-3",
                      Patterns::Double(0.),
                      "Time step Δt of the implicit (backward Euler) "
                      "integration [s].");
    prm.declare_entry("Number of steps",
                      "10",
                      Patterns::Integer(1),
                      "How many time steps the run takes.");
    prm.declare_entry("Output interval",
                      "1",
                      Patterns::Integer(1),
                      "Write the fields (VTU) every this many steps; the CSV "
                      "tables get every step.");
    prm.leave_subsection();
  }

  void
  TimeParameters::parse(ParameterHandler &prm)
  {
    prm.enter_subsection("Time");
    time_step       = prm.get_double("Time step");
    n_steps         = prm.get_integer("Number of steps");
    output_interval = prm.get_integer("Output interval");
    prm.leave_subsection();
    if (!(time_step > 0.))
      throw InputError("Time/Time step",
                       to_string(time_step),
                       "it must be > 0 s.");
  }

  void
  MembraneParameters::declare(ParameterHandler &prm)
  {
    prm.enter_subsection("Membrane");
    prm.declare_entry("Elastic law",
                      "neo-Hookean",
                      Patterns::Selection("neo-Hookean|Skalak"),
                      "In-plane hyperelastic law, in the principal stretches "
                      "λ1, λ2 of the surface deformation. neo-Hookean (the "
                      "paper's): W = C1 (λ1² + λ2² + 1/(λ1λ2)² - 3) + C2/2 "
                      "(λ1λ2 - 1)², C1 = G/2, C2 = K - 3G. Skalak: W = G/4 "
                      "(I1² + 2 I1 - 2 I2 + C I2²), I1 = λ1² + λ2² - 2, I2 = "
                      "(λ1λ2)² - 1, C = (K/G - 1)/2.");
    prm.declare_entry("Shear modulus",
                      "5.5",
                      Patterns::Double(0.),
                      "In-plane shear modulus G [pN/µm]; 5.5 pN/µm is the "
                      "value optical-tweezers experiments give (Mills et al. "
                      "2004: 5.3-7.3).");
    prm.declare_entry("Area dilation modulus",
                      "500",
                      Patterns::Double(0.),
                      "Local area dilation modulus K [pN/µm] (small-strain "
                      "tension per relative area change). The real membrane's "
                      "is ~3e5 pN/µm; 500 keeps local area changes below ~2% "
                      "at 200 pN while the solver stays fast. Must be > 3G "
                      "for the neo-Hookean law.");
    prm.declare_entry("Bending modulus",
                      "0.2",
                      Patterns::Double(0.),
                      "Helfrich bending modulus κ [pN µm]; 0.2 pN µm is "
                      "2e-19 J.");
    prm.declare_entry("Spontaneous curvature",
                      "0",
                      Patterns::Double(),
                      "Spontaneous (total) curvature c0 of the Helfrich energy "
                      "κ/2 ∫ (2H - c0)² dA [1/µm]; 2H = 2/R on a sphere of "
                      "radius R with outward normals.");
    prm.declare_entry("Area penalty",
                      "500",
                      Patterns::Double(0.),
                      "k_A of the global area energy k_A/2 (A - A0)²/A0 "
                      "[pN/µm].");
    prm.declare_entry("Volume penalty",
                      "500",
                      Patterns::Double(0.),
                      "k_V of the global volume energy k_V/2 (V - V0)²/V0 "
                      "[pN/µm²].");
    prm.declare_entry("Finite element degree",
                      "1",
                      Patterns::Integer(1, 2),
                      "Degree k of the membrane's FESystem<2,3>(FE_Q<2,3>(k), "
                      "3) position field.");
    prm.leave_subsection();
  }

  void
  MembraneParameters::parse(ParameterHandler &prm)
  {
    prm.enter_subsection("Membrane");
    law                   = prm.get("Elastic law");
    shear_modulus         = prm.get_double("Shear modulus");
    area_dilation_modulus = prm.get_double("Area dilation modulus");
    bending_modulus       = prm.get_double("Bending modulus");
    spontaneous_curvature = prm.get_double("Spontaneous curvature");
    area_penalty          = prm.get_double("Area penalty");
    volume_penalty        = prm.get_double("Volume penalty");
    degree                = prm.get_integer("Finite element degree");
    prm.leave_subsection();
    if (!(shear_modulus > 0.))
      throw InputError("Membrane/Shear modulus",
                       to_string(shear_modulus),
                       "it must be > 0 pN/µm.");
    if (law == "neo-Hookean" && !(area_dilation_modulus >= 3. * shear_modulus))
      throw InputError(
        "Membrane/Area dilation modulus",
        to_string(area_dilation_modulus),
        "the neo-Hookean law needs K ≥ 3 G = " + to_string(3. * shear_modulus) +
          " pN/µm (its C2 = K - 3G; K = 3G is the classical thin-shell law).");
    if (law == "Skalak" && !(area_dilation_modulus > shear_modulus))
      throw InputError("Membrane/Area dilation modulus",
                       to_string(area_dilation_modulus),
                       "the Skalak law needs K > G = " +
                         to_string(shear_modulus) +
                         " pN/µm (its C = (K/G - 1)/2 > 0).");
  }

  void
  ImmersedParameters::declare(ParameterHandler &prm)
  {
    prm.enter_subsection("Immersed cells");
    prm.declare_entry("Enabled",
                      "false",
                      Patterns::Bool(),
                      "Experiment flow: true carries the red cells of "
                      "subsection Layout in the plasma (the immersed finite "
                      "element method: membrane forces spread to the fluid, "
                      "membranes moved with the interpolated velocity); false "
                      "solves for the plasma alone.");
    prm.declare_entry("Follow cells",
                      "true",
                      Patterns::Bool(),
                      "Move the computational frame with the cells: after "
                      "every step the frame velocity (Fluid/Frame velocity is "
                      "its start value) becomes the cells' mean velocity along "
                      "x, so a cell stays in the short segment. false keeps "
                      "Fluid/Frame velocity.");
    prm.declare_entry("Diffusion interval",
                      "0",
                      Patterns::Integer(0),
                      "Solve the CO diffusion on the current membrane shapes "
                      "at the start and every this many steps (a row of "
                      "dm.csv, the P field and the flux map); 0: never.");
    prm.declare_entry("Checkpoint interval",
                      "0",
                      Patterns::Integer(0),
                      "Write Output directory/checkpoint.bin every this many "
                      "steps (and at the last step); 0: never.");
    prm.declare_entry("Resume",
                      "false",
                      Patterns::Bool(),
                      "Continue from Output directory/checkpoint.bin, written "
                      "by an earlier run of the same file on the same number "
                      "of MPI ranks, up to Time/Number of steps.");
    prm.declare_entry("Progress interval",
                      "10",
                      Patterns::Integer(1),
                      "Print a progress line (step, time, solver iterations, "
                      "frame velocity, volume change and deformation index of "
                      "cell 0) every this many steps, and at every diffusion "
                      "solve (with DM) and output.");
    prm.declare_entry("Maximum step displacement",
                      "0.25",
                      Patterns::Double(0.),
                      "The run stops, as diverged, if a membrane point moves "
                      "farther than this fraction of the fluid mesh size in "
                      "one step (the explicit coupling is then unstable or "
                      "inaccurate: reduce Time/Time step).");
    prm.declare_entry("Tether stiffness",
                      "0",
                      Patterns::Double(0.),
                      "0: the cells are free. > 0: every membrane point is "
                      "held at its starting position by a spring of this "
                      "stiffness [pN/µm], so the cells stay put and flow.csv's "
                      "held_force_x/y/z is the total force that holds them, "
                      "the drag's opposite (the held sphere of "
                      "doc/validation.md). Needs Follow cells = false.");
    prm.leave_subsection();
  }

  void
  ImmersedParameters::parse(ParameterHandler &prm)
  {
    prm.enter_subsection("Immersed cells");
    enabled               = prm.get_bool("Enabled");
    follow_cells          = prm.get_bool("Follow cells");
    diffusion_interval    = prm.get_integer("Diffusion interval");
    checkpoint_interval   = prm.get_integer("Checkpoint interval");
    resume                = prm.get_bool("Resume");
    max_step_displacement = prm.get_double("Maximum step displacement");
    progress_interval     = prm.get_integer("Progress interval");
    tether_stiffness      = prm.get_double("Tether stiffness");
    prm.leave_subsection();
    if (tether_stiffness > 0. && follow_cells)
      throw InputError(
        "Immersed cells/Follow cells",
        "true",
        "held cells (Immersed cells/Tether stiffness = " +
          to_string(tether_stiffness) +
          " pN/µm) need a frame at rest: set Follow cells = false.");
    if (!(max_step_displacement > 0.))
      throw InputError("Immersed cells/Maximum step displacement",
                       to_string(max_step_displacement),
                       "it must be > 0 (a fraction of the fluid mesh size).");
  }

  void
  StretchingParameters::declare(ParameterHandler &prm)
  {
    prm.enter_subsection("Stretching");
    prm.declare_entry("Maximum force",
                      "200",
                      Patterns::Double(0.),
                      "Experiment 'stretching': the largest total force F "
                      "each bead pulls with [pN].");
    prm.declare_entry("Number of force steps",
                      "8",
                      Patterns::Integer(1),
                      "Equilibria at F = 0 and at this many equal steps up to "
                      "the maximum force.");
    prm.declare_entry("Attached area fraction",
                      "0.025",
                      Patterns::Double(0., 0.25),
                      "Fraction of the membrane area each bead holds, at the "
                      "two ends of a diameter. 0.025 is a contact region about "
                      "2 µm across, as Dao et al. (2003) assume for the beads "
                      "of the experiments.");
    prm.declare_entry("Residual tolerance",
                      "1e-3",
                      Patterns::Double(0.),
                      "An equilibrium is found when no node's force "
                      "imbalance exceeds this [pN].");
    prm.declare_entry("Max iterations",
                      "20000",
                      Patterns::Integer(1),
                      "L-BFGS iterations allowed per force step before the "
                      "run stops.");
    prm.leave_subsection();
  }

  void
  ShearParameters::declare(ParameterHandler &prm)
  {
    prm.enter_subsection("Shear");
    prm.declare_entry("Shear rate",
                      "100",
                      Patterns::Double(0.),
                      "Experiment 'shear': the rate γ̇ of the simple shear "
                      "v = (γ̇ y, 0, 0) the box walls impose [1/s]. Results "
                      "depend on it only through the capillary number.");
    prm.declare_entry("Capillary numbers",
                      "0.0125, 0.025, 0.05, 0.1, 0.2",
                      Patterns::List(Patterns::Double(0.), 1),
                      "One run per Ca = μ a γ̇ / G, a the capsule radius "
                      "(Cells/Diameter / 2) and G the membrane's shear "
                      "modulus: every modulus of subsection Membrane is "
                      "scaled by the same factor to give this G, so their "
                      "ratios are kept.");
    prm.declare_entry("Box size",
                      "24, 24, 24",
                      Patterns::List(Patterns::Double(0.), 3, 3, ","),
                      "Length (x, the flow direction; the ends x = ±L/2 are "
                      "open), height (y, between the moving walls) and width "
                      "(z, walls moving with the shear) of the box, centred "
                      "on the capsule [µm]. Each must be a multiple of "
                      "Cells/Diameter, the coarse mesh's cell size.");
    prm.declare_entry("Total strain",
                      "4",
                      Patterns::Double(0.),
                      "Each run lasts until γ̇ t reaches this.");
    prm.declare_entry("Averaging strain",
                      "0.5",
                      Patterns::Double(0.),
                      "The steady deformation is the mean over the steadiest "
                      "window of this length in γ̇ t: the one over which D "
                      "changes least. Without bending stiffness the membrane "
                      "of a capsule at small Ca wrinkles late in a run and D "
                      "creeps up (doc/validation.md); the window finds the "
                      "plateau before that.");
    prm.declare_entry("Output strain interval",
                      "0.25",
                      Patterns::Double(0.),
                      "A shear.csv row, a cells.csv row and the VTU files "
                      "every γ̇ t of this length.");
    prm.declare_entry("Time step fraction",
                      "0.5",
                      Patterns::Double(0., 1.),
                      "Δt of each run as a fraction of its explicit-coupling "
                      "time step limit (doc/ifem.md), which scales with 1/G: "
                      "small Ca take more steps. Time/Time step is not used.");
    prm.leave_subsection();
  }

  void
  ShearParameters::parse(ParameterHandler &prm)
  {
    prm.enter_subsection("Shear");
    shear_rate        = prm.get_double("Shear rate");
    capillary_numbers = Utilities::string_to_double(
      Utilities::split_string_list(prm.get("Capillary numbers")));
    const std::vector<double> size = Utilities::string_to_double(
      Utilities::split_string_list(prm.get("Box size")));
    for (unsigned int d = 0; d < 3; ++d)
      box[d] = size[d];
    strain             = prm.get_double("Total strain");
    averaging_strain   = prm.get_double("Averaging strain");
    output_strain      = prm.get_double("Output strain interval");
    time_step_fraction = prm.get_double("Time step fraction");
    prm.leave_subsection();
  }

  void
  ShearParameters::validate(const CellParameters &cells) const
  {
    require_positive("Cells/Diameter", cells.diameter);
    require_positive("Shear/Shear rate", shear_rate, " 1/s");
    require_positive("Shear/Total strain", strain, "");
    require_positive("Shear/Output strain interval", output_strain, "");
    require_positive("Shear/Time step fraction", time_step_fraction, "");
    for (const double ca : capillary_numbers)
      require_positive("Shear/Capillary numbers", ca, "");
    if (!(averaging_strain > 0. && averaging_strain < strain))
      throw InputError("Shear/Averaging strain",
                       to_string(averaging_strain),
                       "it must be > 0 and below Shear/Total strain = " +
                         to_string(strain) + ".");
    const char *names[] = {"length", "height", "width"};
    for (unsigned int d = 0; d < 3; ++d)
      {
        const double cells_across = box[d] / cells.diameter;
        if (!(cells_across >= 2. &&
              std::abs(cells_across - std::round(cells_across)) < 1e-6))
          throw InputError(
            "Shear/Box size",
            to_string(box[0]) + ", " + to_string(box[1]) + ", " +
              to_string(box[2]),
            std::string("the box ") + names[d] +
              " must be a multiple of Cells/Diameter = " +
              to_string(cells.diameter) +
              " µm, at least twice it, so that the capsule fits.");
      }
  }

  void
  StretchingParameters::parse(ParameterHandler &prm)
  {
    prm.enter_subsection("Stretching");
    max_force         = prm.get_double("Maximum force");
    n_force_steps     = prm.get_integer("Number of force steps");
    attached_fraction = prm.get_double("Attached area fraction");
    tolerance         = prm.get_double("Residual tolerance");
    max_iterations    = prm.get_integer("Max iterations");
    prm.leave_subsection();
    if (!(attached_fraction > 0.))
      throw InputError("Stretching/Attached area fraction",
                       to_string(attached_fraction),
                       "it must be > 0: the beads must hold some membrane.");
    if (!(tolerance > 0.))
      throw InputError("Stretching/Residual tolerance",
                       to_string(tolerance),
                       "it must be > 0 pN.");
  }

  void
  DiffusionParameters::declare(ParameterHandler &prm)
  {
    prm.enter_subsection("Diffusion");
    prm.declare_entry(
      "Alveolar pressure",
      "1",
      Patterns::Double(0.),
      "CO partial pressure P_A on the outer surface of the gas "
      "layer [Torr]. DM = CO flow / P_A does not depend on it.");
    const auto declare_material = [&](const std::string &name,
                                      const std::string &diffusivity,
                                      const std::string &solubility,
                                      const std::string &note) {
      prm.declare_entry(name + " diffusivity",
                        diffusivity,
                        Patterns::Double(0.),
                        "CO diffusion coefficient D in the " + note +
                          " [µm²/s].");
      prm.declare_entry(
        name + " solubility",
        solubility,
        Patterns::Double(0.),
        "CO solubility α in the " + note +
          " [Torr⁻¹, volume of CO (STPD) per volume per Torr].");
    };
    declare_material("Plasma",
                     "2.453e3",
                     "2.363e-5",
                     "plasma (lumen; paper, Table 2)");
    declare_material("Wall",
                     "2.453e3",
                     "2.363e-5",
                     "vessel wall tissue (paper, Table 2)");
    declare_material("Gas",
                     "2.413e7",
                     "1.159e-3",
                     "alveolar gas. D from the paper's Table 2; α of an ideal "
                     "gas at 37 °C in the same units: (1/760) (273.15/310.15) "
                     "= 1.159e-3");
    prm.declare_entry(
      "Finite element degree",
      "1",
      Patterns::Integer(1, 3),
      "Degree k of the continuous FE_Q<3>(k) for P (the mapping "
      "has the same degree).");
    prm.declare_entry("Augmentation",
                      "30",
                      Patterns::Double(0.),
                      "Augmented-Lagrangian weight γ (dimensionless) of the "
                      "membrane constraint. It does not change the solution, "
                      "only the solver: larger γ makes the multiplier block "
                      "easier and the P block harder. See doc/diffusion.md.");
    prm.declare_entry("Linear solver tolerance",
                      "1e-8",
                      Patterns::Double(0.),
                      "FGMRES stops when the residual has fallen by this "
                      "factor.");
    prm.declare_entry("Max linear iterations",
                      "1000",
                      Patterns::Integer(1),
                      "FGMRES gives up (and the run stops) after this many "
                      "iterations.");
    prm.leave_subsection();
  }

  void
  DiffusionParameters::parse(ParameterHandler &prm)
  {
    prm.enter_subsection("Diffusion");
    alveolar_pressure     = prm.get_double("Alveolar pressure");
    plasma_diffusivity    = prm.get_double("Plasma diffusivity");
    plasma_solubility     = prm.get_double("Plasma solubility");
    wall_diffusivity      = prm.get_double("Wall diffusivity");
    wall_solubility       = prm.get_double("Wall solubility");
    gas_diffusivity       = prm.get_double("Gas diffusivity");
    gas_solubility        = prm.get_double("Gas solubility");
    degree                = prm.get_integer("Finite element degree");
    augmentation          = prm.get_double("Augmentation");
    linear_tolerance      = prm.get_double("Linear solver tolerance");
    max_linear_iterations = prm.get_integer("Max linear iterations");
    prm.leave_subsection();
    const std::pair<const char *, double> positive[] = {
      {"Diffusion/Alveolar pressure", alveolar_pressure},
      {"Diffusion/Plasma diffusivity", plasma_diffusivity},
      {"Diffusion/Plasma solubility", plasma_solubility},
      {"Diffusion/Wall diffusivity", wall_diffusivity},
      {"Diffusion/Wall solubility", wall_solubility},
      {"Diffusion/Gas diffusivity", gas_diffusivity},
      {"Diffusion/Gas solubility", gas_solubility},
      {"Diffusion/Augmentation", augmentation},
      {"Diffusion/Linear solver tolerance", linear_tolerance}};
    for (const auto &[name, value] : positive)
      if (!(value > 0.))
        throw InputError(name, to_string(value), "it must be > 0.");
  }

  double
  DiffusionParameters::permeability(const unsigned int material_id) const
  {
    switch (material_id)
      {
        case Material::plasma:
          return plasma_solubility * plasma_diffusivity;
        case Material::vessel_wall:
          return wall_solubility * wall_diffusivity;
        case Material::gas:
          return gas_solubility * gas_diffusivity;
        default:
          throw std::logic_error("no CO diffusion data for material id " +
                                 std::to_string(material_id));
      }
  }

  void
  LayoutStudyParameters::declare(ParameterHandler &prm)
  {
    prm.enter_subsection("Layout study");
    prm.declare_entry(
      "Kinds",
      "uniform, random, clustered",
      Patterns::List(Patterns::Selection("uniform|random|clustered"), 1),
      "Experiment 'layouts': the layout kinds to compare.");
    prm.declare_entry("Numbers of cells",
                      "1, 2, 3, 4, 5, 6, 7",
                      Patterns::List(Patterns::Integer(1), 1),
                      "Experiment 'layouts': the numbers of cells N to place "
                      "in the segment, each in every kind.");
    prm.declare_entry("Random seeds",
                      "5",
                      Patterns::Integer(1),
                      "Experiment 'layouts': random layouts are drawn with "
                      "seeds Layout/Seed, Layout/Seed + 1, ...; layouts.csv "
                      "reports their mean and spread.");
    prm.leave_subsection();
  }

  void
  LayoutStudyParameters::parse(ParameterHandler &prm)
  {
    prm.enter_subsection("Layout study");
    kinds = Utilities::split_string_list(prm.get("Kinds"));
    numbers_of_cells.clear();
    for (const int n : Utilities::string_to_int(
           Utilities::split_string_list(prm.get("Numbers of cells"))))
      numbers_of_cells.push_back(n);
    n_seeds = prm.get_integer("Random seeds");
    prm.leave_subsection();
  }

  void
  MeshConvergenceParameters::declare(ParameterHandler &prm)
  {
    prm.enter_subsection("Mesh convergence");
    prm.declare_entry("Number of levels",
                      "4",
                      Patterns::Integer(2, 6),
                      "Experiment 'mesh convergence': level 0 is the mesh of "
                      "subsection Mesh and Cells/Surface refinements; each "
                      "further level refines the diffusion mesh's band and "
                      "the membranes once more.");
    prm.leave_subsection();
  }

  void
  MeshConvergenceParameters::parse(ParameterHandler &prm)
  {
    prm.enter_subsection("Mesh convergence");
    n_levels = prm.get_integer("Number of levels");
    prm.leave_subsection();
  }

  void
  Parameters::declare(ParameterHandler &prm)
  {
    prm.declare_entry(
      "Experiment",
      "geometry",
      Patterns::Selection(
        "geometry|diffusion|layouts|mesh convergence|flow|stretching|shear"),
      "What to run. geometry: build the fluid and diffusion "
      "meshes and the cell layout, and write them out. "
      "diffusion: steady CO uptake of the layout (dm.csv, "
      "VTU of P and of the membrane flux). layouts: DM for "
      "every kind and number of cells of subsection Layout "
      "study (layouts.csv). mesh convergence: DM of the "
      "layout on successively finer meshes (convergence.csv). "
      "flow: the plasma flow in the capillary for Time/Number "
      "of steps (flow.csv, VTU of v and p), with the cells of "
      "subsection Layout in it if Immersed cells/Enabled "
      "(cells.csv, dm.csv, VTU of the membranes). "
      "stretching: one cell pulled by two beads with forces "
      "up to Stretching/Maximum force (stretch.csv, VTU of "
      "each equilibrium). shear: a spherical capsule in "
      "simple shear for each Shear/Capillary numbers "
      "(shear.csv per run, shear_summary.csv).");
    prm.declare_entry("Output directory",
                      "output/run",
                      Patterns::DirectoryName(),
                      "Where the run writes its files; created if needed.");
    GeometryParameters::declare(prm);
    MeshParameters::declare(prm);
    CellParameters::declare(prm);
    LayoutParameters::declare(prm);
    FluidParameters::declare(prm);
    TimeParameters::declare(prm);
    MembraneParameters::declare(prm);
    ImmersedParameters::declare(prm);
    StretchingParameters::declare(prm);
    ShearParameters::declare(prm);
    DiffusionParameters::declare(prm);
    LayoutStudyParameters::declare(prm);
    MeshConvergenceParameters::declare(prm);
  }

  void
  Parameters::parse(ParameterHandler &prm)
  {
    experiment       = prm.get("Experiment");
    output_directory = prm.get("Output directory");
    if (output_directory.empty() ||
        (std::filesystem::exists(output_directory) &&
         !std::filesystem::is_directory(output_directory)))
      throw InputError(
        "Output directory",
        output_directory,
        "it must name a directory, new or existing, not a file.");
    geometry.parse(prm);
    mesh.parse(prm);
    cells.parse(prm);
    layout.parse(prm);
    fluid.parse(prm);
    time.parse(prm);
    membrane.parse(prm);
    immersed.parse(prm);
    stretching.parse(prm);
    shear.parse(prm);
    diffusion.parse(prm);
    layout_study.parse(prm);
    mesh_convergence.parse(prm);
    geometry.validate();
    // The shear box replaces the capillary.
    if (experiment == "shear")
      shear.validate(cells);
    else
      cells.validate(geometry);
    if (experiment == "flow" && immersed.enabled && layout.n_cells == 0)
      throw InputError(
        "Layout/Number of cells",
        "0",
        "a flow with Immersed cells/Enabled = true needs at least one cell.");
  }

  void
  read_parameters(const std::string &filename,
                  ParameterHandler  &prm,
                  Parameters        &parameters)
  {
    if (!std::filesystem::is_regular_file(filename) || !std::ifstream(filename))
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
