/* ---------------------------------------------------------------------
 * rbc-ifem tutorial step-2: a red cell pulled by optical tweezers.
 *
 * The membrane alone: an Evans-Fung cell whose membrane is a hyperelastic
 * shell (Skalak or neo-Hookean in-plane, Helfrich bending, area and volume
 * held by penalties), pulled along a diameter by two beads. For each bead
 * force the static equilibrium is found, and the cell's axial and
 * transverse diameters are the stretch curve that Mills et al. (2004)
 * measured. examples/step-2/README.md is this program's page.
 * --------------------------------------------------------------------- */

#include <rbc_ifem/base/csv.h>
#include <rbc_ifem/base/output.h>
#include <rbc_ifem/geometry/cell_surface.h>
#include <rbc_ifem/geometry/evans_fung.h>
#include <rbc_ifem/membrane/membrane.h>
#include <rbc_ifem/membrane/membrane_equilibrium.h>
#include <rbc_ifem/membrane/optical_tweezers.h>
#include <rbc_ifem/parameters.h>

#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>

#include <iomanip>
#include <iostream>

using namespace dealii;
using namespace rbc_ifem;

// @sect3{A subsection of one's own}
//
// The library's parameter structs each declare their subsection; a program
// adds its own the same way, with ParameterHandler::add_parameter(), which
// takes the default from the member and binds the member to the entry.
struct TweezersParameters
{
  double       max_force         = 200.; // [pN] on each bead
  unsigned int n_force_steps     = 8;
  double       attached_fraction = 0.025; // of the membrane area, per bead

  void
  add_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Tweezers");
    prm.add_parameter("Maximum force", max_force, "[pN]", Patterns::Double(0.));
    prm.add_parameter("Number of force steps",
                      n_force_steps,
                      "",
                      Patterns::Integer(1));
    prm.add_parameter("Attached area fraction",
                      attached_fraction,
                      "of the membrane area, per bead",
                      Patterns::Double(0., 0.5));
    prm.leave_subsection();
  }
};

int
main(int argc, char *argv[])
{
  // The membrane problem is small (a few thousand DoFs) and serial.
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);

  Parameters         parameters;
  TweezersParameters tweezers;
  ParameterHandler   prm;
  parameters.add_parameters(prm);
  tweezers.add_parameters(prm);
  prm.parse_input(argc > 1 ? argv[1] : "step-2.prm");
  parameters.validate();

  // @sect3{The membrane}
  //
  // The cell's reference surface: the exact Evans-Fung shape, its disc in
  // the x-y plane (its axis along z), meshed by refining an inscribed
  // cube's faces. Membrane puts a vector-valued FE_Q<2,3> on it: the
  // positions x of its nodes are the unknowns, and it gives the energy
  // E(x) and its exact negative gradient, the nodal forces (Sacado).
  Triangulation<2, 3> surface;
  create_cell_surface(surface,
                      EvansFungShape::of(parameters.cells),
                      CellPlacement{Point<3>(), Tensor<1, 3>({0., 0., 1.})},
                      parameters.cells.surface_refinements);
  const Membrane membrane(surface, parameters.membrane);
  std::cout << parameters.membrane.law
            << " membrane, G = " << parameters.membrane.shear_modulus
            << " pN/µm: " << surface.n_active_cells() << " cells, "
            << membrane.get_dof_handler().n_dofs() << " DoFs" << std::endl;

  // @sect3{The beads}
  //
  // Each bead holds a patch at one end of the diameter along x, and pulls
  // with its force spread over the patch's nodes by their areas:
  // bead_forces() is that pull for 1 pN.
  const Vector<double> unit_pull =
    bead_forces(membrane, tweezers.attached_fraction);

  // @sect3{The stretch curve}
  //
  // For each force F the equilibrium minimises Π(x) = E(x) - F f·x;
  // find_equilibrium() runs L-BFGS from the previous equilibrium, which is
  // close, until the largest nodal force imbalance is below 1e-3 pN.
  CsvTable       table("force,axial_diameter,transverse_diameter");
  Vector<double> x = membrane.reference_positions();
  for (unsigned int step = 0; step <= tweezers.n_force_steps; ++step)
    {
      const double   force = tweezers.max_force * step / tweezers.n_force_steps;
      Vector<double> pull(unit_pull);
      pull *= force;
      const EquilibriumReport report =
        find_equilibrium(membrane, pull, x, 1e-3, 20000);
      const StretchDiameters d = stretch_diameters(membrane, x);
      std::cout << "F = " << std::setw(5) << force << " pN: axial "
                << std::setw(8) << d.axial << " µm, transverse " << std::setw(8)
                << d.transverse << " µm (" << report.iterations
                << " L-BFGS iterations)" << std::endl;
      table.add(force, d.axial, d.transverse);
    }

  // The table in the columns of rbc-ifem's stretch.csv, so that
  // doc/scripts/plot_stretch.py draws it against the measurements.
  create_output_directory(parameters.output_directory, MPI_COMM_SELF);
  table.write(parameters.output_directory + "/stretch.csv");
  std::cout << "wrote " << parameters.output_directory << "/stretch.csv"
            << std::endl;
}
