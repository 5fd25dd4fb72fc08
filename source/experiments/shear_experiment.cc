#include <rbc_ifem/base/output.h>
#include <rbc_ifem/coupling/cell_population.h>
#include <rbc_ifem/experiments/shear_experiment.h>
#include <rbc_ifem/ifem/flow_domain.h>
#include <rbc_ifem/ifem/ifem_simulation.h>

#include <deal.II/base/timer.h>

#include <cmath>
#include <iomanip>
#include <limits>
#include <sstream>

namespace rbc_ifem
{
  namespace
  {
    std::string
    to_text(const double value)
    {
      std::ostringstream text;
      text << std::setprecision(10) << value;
      return text.str();
    }

    /// A copy of @p prm with the parameters of one run set in it.
    void
    copy_parameters(const ParameterHandler &prm, ParameterHandler &copy)
    {
      Parameters::declare(copy);
      std::ostringstream text;
      prm.print_parameters(text, ParameterHandler::PRM);
      copy.parse_input_from_string(text.str());
    }
  } // namespace

  ShearExperiment::ShearExperiment(const Parameters &parameters,
                                   const MPI_Comm    communicator)
    : parameters(parameters)
    , communicator(communicator)
    , pcout(std::cout, Utilities::MPI::this_mpi_process(communicator) == 0)
  {
    // The capsule's mesh and the fluid mesh around it do not depend on Ca:
    // the box's coarse cells have the capsule's diameter as edge, halved by
    // every global and band refinement.
    point_spacing = CellPopulation(FlowDomain::shear_box(parameters).placements,
                                   parameters.cells,
                                   parameters.membrane)
                      .point_spacing();
    mesh_size = parameters.cells.diameter /
                std::pow(2.,
                         parameters.mesh.fluid_global_refinements +
                           parameters.mesh.fluid_band_refinements);
  }

  Parameters
  ShearExperiment::parameters_for(const double capillary_number) const
  {
    Parameters             p      = parameters;
    const ShearParameters &shear  = parameters.shear;
    const double           factor = p.fluid.viscosity * p.cells.diameter / 2. *
                          shear.shear_rate /
                          (capillary_number * p.membrane.shear_modulus);
    for (double *modulus : {&p.membrane.shear_modulus,
                            &p.membrane.area_dilation_modulus,
                            &p.membrane.bending_modulus,
                            &p.membrane.area_penalty,
                            &p.membrane.volume_penalty})
      *modulus *= factor;

    p.immersed.enabled             = true;
    p.immersed.follow_cells        = false;
    p.immersed.diffusion_interval  = 0;
    p.immersed.checkpoint_interval = 0;
    p.immersed.resume              = false;
    p.fluid.frame_velocity         = 0.;

    // Whole steps to the total strain, each within the fraction of the limit.
    const CouplingTimeStepLimit limit(p.fluid.viscosity,
                                      p.membrane,
                                      point_spacing,
                                      mesh_size);
    const double                largest_strain_step =
      shear.time_step_fraction * limit.limit * shear.shear_rate;
    p.time.n_steps =
      static_cast<unsigned int>(std::ceil(shear.strain / largest_strain_step));
    p.time.time_step = shear.strain / shear.shear_rate / p.time.n_steps;
    p.time.output_interval =
      std::max(1l,
               std::lround(shear.output_strain /
                           (shear.shear_rate * p.time.time_step)));
    p.immersed.progress_interval = p.time.output_interval;
    p.output_directory =
      parameters.output_directory + "/ca_" + to_text(capillary_number);
    return p;
  }

  ShearSummary
  ShearExperiment::steady_state(
    const std::vector<std::array<double, 3>> &history) const
  {
    // The samples are one output interval apart (the last one may be
    // closer); a window holds the samples spanning Averaging strain.
    const double       rate     = parameters.shear.shear_rate;
    const double       spacing  = rate * (history[1][0] - history[0][0]);
    const unsigned int n_window = std::min<unsigned int>(
      history.size(),
      std::lround(parameters.shear.averaging_strain / spacing) + 1);
    ShearSummary best;
    double       least_change = std::numeric_limits<double>::infinity();
    for (unsigned int first = 0; first + n_window <= history.size(); ++first)
      {
        double low = history[first][1], high = low, deformation = 0.,
               inclination = 0.;
        for (unsigned int i = first; i < first + n_window; ++i)
          {
            low  = std::min(low, history[i][1]);
            high = std::max(high, history[i][1]);
            deformation += history[i][1];
            inclination += history[i][2] / numbers::PI;
          }
        if (high - low < least_change)
          {
            least_change            = high - low;
            best.steady_deformation = deformation / n_window;
            best.steady_inclination = inclination / n_window;
            best.steady_from        = rate * history[first][0];
            best.steady_to          = rate * history[first + n_window - 1][0];
          }
      }
    return best;
  }

  ShearSummary
  ShearExperiment::run_one(const double            capillary_number,
                           const ParameterHandler &prm) const
  {
    const Parameters p = parameters_for(capillary_number);
    ParameterHandler used;
    copy_parameters(prm, used);
    used.set("Output directory", p.output_directory);
    used.enter_subsection("Membrane");
    used.set("Shear modulus", to_text(p.membrane.shear_modulus));
    used.set("Area dilation modulus",
             to_text(p.membrane.area_dilation_modulus));
    used.set("Bending modulus", to_text(p.membrane.bending_modulus));
    used.set("Area penalty", to_text(p.membrane.area_penalty));
    used.set("Volume penalty", to_text(p.membrane.volume_penalty));
    used.leave_subsection();
    used.enter_subsection("Time");
    used.set("Time step", to_text(p.time.time_step));
    used.set("Number of steps", to_text(p.time.n_steps));
    used.set("Output interval", to_text(p.time.output_interval));
    used.leave_subsection();

    pcout << "\nCa = " << capillary_number
          << ": G = " << p.membrane.shear_modulus
          << " pN/µm, Δt = " << p.time.time_step
          << " s (γ̇ Δt = " << parameters.shear.shear_rate * p.time.time_step
          << "), " << p.time.n_steps << " steps, in " << p.output_directory
          << std::endl;
    Timer          clock;
    IFEMSimulation simulation(p, communicator, FlowDomain::shear_box(p));
    simulation.run(used);

    ShearSummary summary = steady_state(simulation.run_record().shear_history);
    summary.capillary_number = capillary_number;
    summary.time_step        = p.time.time_step;
    summary.n_steps          = p.time.n_steps;
    summary.wall_seconds     = clock.wall_time();
    pcout << "Ca = " << capillary_number << ": steady Taylor deformation "
          << summary.steady_deformation << ", inclination "
          << summary.steady_inclination
          << " π (means over γ̇ t = " << summary.steady_from << " to "
          << summary.steady_to << ", where D changes least)" << std::endl;
    return summary;
  }

  void
  ShearExperiment::run(const ParameterHandler &prm)
  {
    const ShearParameters &shear = parameters.shear;
    pcout << "rbc-ifem: experiment 'shear': a spherical capsule of radius "
          << parameters.cells.diameter / 2. << " µm ("
          << parameters.membrane.law
          << ") in simple shear γ̇ = " << shear.shear_rate << " 1/s, box "
          << shear.box[0] << " x " << shear.box[1] << " x " << shear.box[2]
          << " µm, " << shear.capillary_numbers.size()
          << " capillary number(s), to γ̇ t = " << shear.strain << std::endl;
    const std::string &directory = parameters.output_directory;
    create_output_directory(directory, communicator);
    if (Utilities::MPI::this_mpi_process(communicator) == 0)
      write_file_atomically(directory + "/parameters.prm",
                            [&](std::ostream &out) {
                              prm.print_parameters(out, ParameterHandler::PRM);
                            });

    std::vector<ShearSummary> summaries;
    for (const double capillary_number : shear.capillary_numbers)
      {
        summaries.push_back(run_one(capillary_number, prm));
        if (Utilities::MPI::this_mpi_process(communicator) == 0)
          write_file_atomically(
            directory + "/shear_summary.csv", [&](std::ostream &out) {
              out
                << "capillary_number,steady_deformation,steady_inclination_over_pi,"
                   "steady_from_strain,steady_to_strain,time_step,n_steps,wall_seconds\n"
                << std::setprecision(10);
              for (const ShearSummary &s : summaries)
                out << s.capillary_number << ',' << s.steady_deformation << ','
                    << s.steady_inclination << ',' << s.steady_from << ','
                    << s.steady_to << ',' << s.time_step << ',' << s.n_steps
                    << ',' << s.wall_seconds << '\n';
            });
      }
    pcout
      << "\nwrote " << directory
      << "/: parameters.prm, shear_summary.csv and a directory "
      << "ca_<Ca>/ per run (shear.csv, cells.csv, flow.csv, flow.pvd, cell_0.pvd, timing.csv)"
      << std::endl;
  }
} // namespace rbc_ifem
