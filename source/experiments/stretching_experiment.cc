#include <rbc_ifem/base/csv.h>
#include <rbc_ifem/base/input_error.h>
#include <rbc_ifem/base/output.h>
#include <rbc_ifem/base/output_error.h>
#include <rbc_ifem/base/parameter_tools.h>
#include <rbc_ifem/base/solver_failure.h>
#include <rbc_ifem/experiments/stretching_experiment.h>
#include <rbc_ifem/geometry/cell_surface.h>
#include <rbc_ifem/membrane/membrane_equilibrium.h>
#include <rbc_ifem/membrane/optical_tweezers.h>

#include <deal.II/base/mpi.h>
#include <deal.II/base/utilities.h>

#include <iomanip>

namespace rbc_ifem
{
  void
  StretchingParameters::add_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Stretching");
    add_parameter(prm,
                  "Maximum force",
                  max_force,
                  "Experiment 'stretching': the largest total force F "
                  "each bead pulls with [pN].",
                  Patterns::Double(0.));
    add_parameter(prm,
                  "Number of force steps",
                  n_force_steps,
                  "Equilibria at F = 0 and at this many equal steps up to "
                  "the maximum force.",
                  Patterns::Integer(1));
    add_parameter(prm,
                  "Attached area fraction",
                  attached_fraction,
                  "Fraction of the membrane area each bead holds, at the "
                  "two ends of a diameter. 0.025 is a contact region about "
                  "2 µm across, as Dao et al. (2003) assume for the beads "
                  "of the experiments.",
                  GreaterThan(0., 0.25));
    add_parameter(prm,
                  "Residual tolerance",
                  tolerance,
                  "An equilibrium is found when no node's force "
                  "imbalance exceeds this [pN].",
                  GreaterThan());
    add_parameter(prm,
                  "Max iterations",
                  max_iterations,
                  "L-BFGS iterations allowed per force step before the "
                  "run stops.",
                  Patterns::Integer(1));
    prm.leave_subsection();
  }

  StretchingExperiment::StretchingExperiment(
    const ExperimentContext    &context,
    const StretchingParameters &stretching)
    : Experiment(context, ParametersFile::after_work)
    , stretching(stretching)
  {}

  void
  StretchingExperiment::setup()
  {
    pcout << "  " << parameters.membrane.law
          << ", G = " << parameters.membrane.shear_modulus
          << " pN/µm, K = " << parameters.membrane.area_dilation_modulus
          << " pN/µm, κ = " << parameters.membrane.bending_modulus << " pN µm"
          << std::endl;
    if (Utilities::MPI::this_mpi_process(communicator) != 0)
      return;
    create_cell_surface(surface,
                        EvansFungShape::of(parameters.cells),
                        CellPlacement{Point<3>(), Tensor<1, 3>({0., 0., 1.})},
                        parameters.cells.surface_refinements);
    membrane = std::make_unique<Membrane>(surface, parameters.membrane);
    pcout << "  membrane: " << surface.n_active_cells() << " cells, "
          << membrane->get_dof_handler().n_dofs() << " DoFs; area "
          << membrane->reference_area() << " µm², volume "
          << membrane->reference_volume() << " µm³" << std::endl;
  }

  void
  StretchingExperiment::execute()
  {
    // Rank 0 works alone; the others must learn if it failed, or they
    // would wait for it in the closing collectives (write_on_rank_0() tells
    // them of a file it could not write).
    std::string failure;
    write_on_rank_0(communicator, [&]() {
      try
        {
          find_equilibria();
        }
      catch (const SolverFailure &e)
        {
          failure = e.what();
        }
    });
    failure = Utilities::MPI::broadcast(communicator, failure, 0);
    if (!failure.empty())
      throw SolverFailure(failure);
  }

  void
  StretchingExperiment::find_equilibria()
  {
    const StretchingParameters &s = stretching;
    const Vector<double>        unit_force =
      bead_forces(*membrane, stretching.attached_fraction);
    Vector<double> x(membrane->reference_positions());

    CsvTable table(
      "force,axial_diameter,transverse_diameter,area,volume,iterations,residual");
    std::vector<std::pair<double, std::string>> shapes;
    std::vector<Vector<double>>                 equilibria;
    Timer                                       clock;
    for (unsigned int step = 0; step <= s.n_force_steps; ++step)
      {
        const double   force = s.max_force * step / s.n_force_steps;
        Vector<double> f(unit_force);
        f *= force;
        EquilibriumReport report;
        {
          TimerOutput::Scope scope(timer, "equilibrium");
          report =
            find_equilibrium(*membrane, f, x, s.tolerance, s.max_iterations);
        }
        const StretchDiameters d = stretch_diameters(*membrane, x);
        const double area = membrane->area(x), volume = membrane->volume(x);
        pcout << "  step " << step << " of " << s.n_force_steps
              << ", F = " << std::setw(6) << force << " pN: " << std::setw(5)
              << report.iterations << " L-BFGS iterations, residual "
              << report.residual << " pN; axial " << d.axial
              << " µm, transverse " << d.transverse << " µm, area "
              << area / membrane->reference_area() << " A0, volume "
              << volume / membrane->reference_volume() << " V0  "
              << time_left_text(clock.wall_time(),
                                step + 1,
                                s.n_force_steps - step)
              << std::endl;
        table.add(force,
                  d.axial,
                  d.transverse,
                  area,
                  volume,
                  report.iterations,
                  report.residual);
        equilibria.push_back(x);
        shapes.emplace_back(force,
                            "stretch_" + Utilities::int_to_string(step, 3));
      }

    // Written only now: a failed equilibrium leaves no table or shape.
    const std::string &directory = parameters.output_directory;
    create_output_directory(directory, MPI_COMM_SELF);
    {
      TimerOutput::Scope scope(timer, "output");
      for (unsigned int k = 0; k < shapes.size(); ++k)
        {
          // The .pvd's "timestep" is the bead force; each file says so.
          membrane->write_vtu(equilibria[k],
                              directory,
                              shapes[k].second,
                              {},
                              {{"BEAD_FORCE", shapes[k].first}});
          shapes[k].second += ".vtu";
        }
    }
    write_pvd(directory, "stretch", shapes, MPI_COMM_SELF);
    table.write(directory + "/stretch.csv");
  }
} // namespace rbc_ifem
