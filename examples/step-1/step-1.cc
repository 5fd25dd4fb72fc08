/* ---------------------------------------------------------------------
 * rbc-ifem tutorial step-1: the CO uptake of one red cell.
 *
 * The smallest complete use of the library: build a pulmonary capillary
 * segment and one Evans-Fung red cell in it, solve the steady diffusion of
 * carbon monoxide from the alveolar gas through the vessel wall and the
 * plasma into the cell, and print the membrane diffusing capacity
 *
 *     DM = (CO flow into the cell) / P_A      [µm³ s⁻¹ Torr⁻¹]
 *
 * with the flux map on the membrane for ParaView. examples/step-1/README.md
 * is this program's page: the physics, the method, the results.
 * --------------------------------------------------------------------- */

// The library's headers, one folder per concern, as in doc/design.md:
// the parameters of every concern, the capillary meshes, the cells, the
// diffusion solver, and the writers of the files a run leaves.
#include <rbc_ifem/base/output.h>
#include <rbc_ifem/base/parameter_text.h>
#include <rbc_ifem/diffusion/co_diffusion.h>
#include <rbc_ifem/diffusion/uptake.h>
#include <rbc_ifem/geometry/capillary_mesh.h>
#include <rbc_ifem/geometry/placed_cells.h>
#include <rbc_ifem/parameters.h>

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/timer.h>
#include <deal.II/distributed/shared_tria.h>

#include <iostream>

using namespace dealii;
using namespace rbc_ifem;

// @sect3{The parameters}
//
// rbc_ifem::Parameters gathers the parameter structs of every concern
// (geometry, mesh, cells, layout, diffusion, ...). Each declares its
// subsection in a ParameterHandler with its members' values as defaults
// and binds the members to it, so that parsing the file fills them; then
// validate() rejects what a pattern cannot (a zero length, say), with
// a message that names the parameter. (The handler keeps the members it
// binds: both live as long as the program.)
void
read_parameters(const std::string &file,
                Parameters        &parameters,
                ParameterHandler  &prm)
{
  parameters.add_parameters(prm);
  prm.parse_input(file);
  parameters.validate();
}

// @sect3{The diffusion mesh}
//
// Three materials in one mesh: the lumen (plasma; the cell interior is
// part of it), the vessel wall and the alveolar gas layer, each with its
// own material id, so that each gets its own solubility times
// diffusivity αD. The membrane cuts through the hexahedra anywhere (the
// meshes do not match); the mesh is refined in a band around it so that
// it resolves the membrane about as finely as the membrane's own cells.
void
make_diffusion_mesh(Triangulation<3>            &mesh,
                    const Parameters            &parameters,
                    const std::vector<Point<3>> &membrane_vertices)
{
  create_diffusion_mesh(mesh,
                        parameters.geometry,
                        parameters.mesh.diffusion_global_refinements);
  refine_near_points(mesh,
                     membrane_vertices,
                     parameters.mesh.band_width,
                     parameters.mesh.diffusion_band_refinements);
}

// @sect3{DM and the flux map}
//
// The CO flow into the cell is ∫ λ dA over its membrane; DM is that
// flow over P_A. What enters the cell must have left the gas: the flow
// through the alveolar surface agrees with it to the discretisation
// error (0.1% here), a check of the solution any user can make.
void
report_uptake(const CODiffusion        &diffusion,
              const Parameters         &parameters,
              const ConditionalOStream &pcout)
{
  const double into_cell = diffusion.membrane_flows()[0];
  const double from_gas  = diffusion.boundary_flow();
  pcout << diffusion.n_pressure_dofs() << " DoFs of P, "
        << diffusion.n_multiplier_dofs() << " of λ; "
        << diffusion.n_iterations() << " FGMRES iterations" << std::endl
        << "CO flow into the cell " << into_cell << " µm³/s, out of the gas "
        << from_gas << " µm³/s" << std::endl
        << "DM = " << into_cell / parameters.diffusion.alveolar_pressure
        << " µm³/(s Torr)" << std::endl;
}

int
main(int argc, char *argv[])
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  const MPI_Comm                   communicator = MPI_COMM_WORLD;
  ConditionalOStream               pcout(std::cout,
                           Utilities::MPI::this_mpi_process(communicator) == 0);
  Parameters                       parameters;
  ParameterHandler                 prm;
  read_parameters(argc > 1 ? argv[1] : "step-1.prm", parameters, prm);

  // @sect3{The red cell}
  //
  // PlacedCells places the cells of subsection Layout (here one, in the
  // middle of the segment, its axis along the capillary) and meshes each
  // membrane as a Triangulation<2,3> on the exact Evans-Fung surface,
  // refined Cells/Surface refinements times. It checks that the cell fits
  // into the lumen and clears the wall.
  const PlacedCells cells(parameters.layout,
                          parameters.geometry,
                          parameters.cells,
                          parameters.cells.surface_refinements);
  pcout << "one red cell of " << parameters.cells.diameter << " µm: volume "
        << cells.membranes.volumes()[0] << " µm³, "
        << cells.membranes.surfaces()[0]->n_active_cells() << " membrane cells"
        << std::endl;

  parallel::shared::Triangulation<3> mesh(
    communicator,
    Triangulation<3>::none,
    false,
    parallel::shared::Triangulation<3>::partition_metis);
  make_diffusion_mesh(mesh, parameters, cells.membranes.vertices());
  pcout << "diffusion mesh: " << mesh.n_active_cells() << " cells, "
        << mesh.n_used_vertices() << " nodes" << std::endl;

  // @sect3{The CO diffusion}
  //
  // ∇·(αD ∇P) = 0 with P = P_A on the outer surface of the gas layer, no
  // flux through the end faces, and P = 0 on the membrane: CO is bound the
  // instant it enters the cell. CODiffusion imposes P = 0 weakly with a
  // Lagrange multiplier λ on the membrane (deal.II's step-60), and λ is the
  // CO flux density into the cell: the flux map. setup() distributes the
  // DoFs of P and λ and locates the membrane's quadrature points in the
  // volume mesh, assemble() builds the matrices and the preconditioner,
  // solve() runs FGMRES on the saddle point problem.
  TimerOutput timer(communicator,
                    pcout,
                    TimerOutput::never,
                    TimerOutput::wall_times);
  CODiffusion diffusion(
    parameters.diffusion,
    [&](const unsigned int material) {
      return parameters.diffusion.permeability(material);
    },
    DiffusionBoundary::alveolar_surface,
    communicator,
    timer);
  diffusion.setup(mesh, cells.membranes.membrane_surfaces());
  diffusion.assemble();
  diffusion.solve();
  report_uptake(diffusion, parameters, pcout);

  // The fields as a run of rbc-ifem writes them: diffusion.pvd (P and the
  // material ids) and diffusion_membranes.pvd (λ as co_flux, and -λ n as
  // co_flux_vector), with parameters.prm, in Output directory.
  const std::string &directory = parameters.output_directory;
  create_output_directory(directory, communicator);
  UptakeFields().write(diffusion, directory, 0., 0, communicator);
  write_parameters(parameter_text(prm), directory, communicator);
  pcout << "wrote " << directory << "/: " << written_files(directory)
        << std::endl;
}
