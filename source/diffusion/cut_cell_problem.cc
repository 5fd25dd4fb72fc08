#include <rbc_ifem/base/output.h>
#include <rbc_ifem/base/solver_failure.h>
#include <rbc_ifem/diffusion/cut_cell_problem.h>
#include <rbc_ifem/diffusion/scaled_amg_solve.h>

#include <deal.II/base/quadrature_lib.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_interface_values.h>
#include <deal.II/fe/fe_nothing.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/la_parallel_vector.h>
#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/sparsity_tools.h>
#include <deal.II/lac/trilinos_index_access.h>

#include <algorithm>
#include <cmath>

namespace rbc_ifem
{
  namespace
  {
    /// The two elements of the hp collection.
    enum ActiveFE : unsigned int
    {
      fields  = 0, ///< cells that reach into a field's side
      nothing = 1  ///< cells on no field's side
    };
  } // namespace

  CutCellProblem::CutCellProblem(
    const CutCellGeometry                     &geometry,
    const DiffusionParameters                 &parameters,
    const std::function<double(unsigned int)> &permeability,
    const types::boundary_id                   pressure_boundary,
    TimerOutput                               &timer)
    : DiffusionSolver(parameters.alveolar_pressure)
    , geometry(geometry)
    , parameters(parameters)
    , permeability(permeability)
    , pressure_boundary(pressure_boundary)
    , communicator(geometry.mesh().get_communicator())
    , timer(timer)
  {}

  CutCellProblem::~CutCellProblem()
  {
    // The DoFHandlers refer to the meshes: release them first.
    dof_handler.clear();
    flux_dof_handlers.clear();
  }

  void
  CutCellProblem::set_up_system(const FiniteElement<3> &fe)
  {
    TimerOutput::Scope scope(timer, "diffusion: DoFs and constraints");
    fe_collection = hp::FECollection<3>(fe, FE_Nothing<3>(fe.n_components()));
    dof_handler.reinit(geometry.mesh());
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        cell->set_active_fe_index(fields_on(cell).empty() ? ActiveFE::nothing :
                                                            ActiveFE::fields);
    dof_handler.distribute_dofs(fe_collection);
    owned_dofs = dof_handler.locally_owned_dofs();
    DoFTools::extract_locally_relevant_dofs(dof_handler, relevant_dofs);

    const IndexSet unused = unused_field_dofs();
    n_unused_dofs =
      Utilities::MPI::sum((unused & owned_dofs).n_elements(), communicator);
    make_pressure_constraints(dof_handler,
                              geometry.mapping(),
                              pressure_boundary,
                              parameters.alveolar_pressure,
                              geometry.period(),
                              constraints,
                              unused);
    set_up_matrix();
  }

  IndexSet
  CutCellProblem::unused_field_dofs() const
  {
    // With one field every DoF of a cell with DoFs is used.
    const FiniteElement<3> &fe = fe_collection[ActiveFE::fields];
    if (fe.n_components() == 1)
      return IndexSet(dof_handler.n_dofs());
    // Marked on the owned cells and summed on the owners, so that the ranks
    // agree on every DoF they share.
    LinearAlgebra::distributed::Vector<double> used(owned_dofs,
                                                    relevant_dofs,
                                                    communicator);
    std::vector<types::global_dof_index>       dofs(fe.n_dofs_per_cell());
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          const std::vector<unsigned int> fields = fields_on(cell);
          cell->get_dof_indices(dofs);
          for (unsigned int i = 0; i < dofs.size(); ++i)
            if (std::count(fields.begin(),
                           fields.end(),
                           fe.system_to_component_index(i).first) > 0)
              used[dofs[i]] = 1.;
        }
    // A used node that hangs on a coarser face needs the nodes it hangs on,
    // whichever side's cell holds them.
    AffineConstraints<double> hanging(relevant_dofs);
    DoFTools::make_hanging_node_constraints(dof_handler, hanging);
    for (const auto &line : hanging.get_lines())
      if (used[line.index] > 0.)
        for (const auto &[dof, weight] : line.entries)
          used[dof] = 1.;
    used.compress(VectorOperation::add);
    used.update_ghost_values();
    IndexSet unused(dof_handler.n_dofs());
    for (const auto dof : relevant_dofs)
      if (used[dof] == 0.)
        unused.add_index(dof);
    unused.compress();
    return unused;
  }

  std::vector<unsigned int>
  CutCellProblem::ghost_penalty_fields(
    const DoFHandler<3>::active_cell_iterator &cell,
    const unsigned int                         face) const
  {
    if (cell->at_boundary(face) || cell->neighbor(face)->has_children())
      return {};
    const auto neighbor = cell->neighbor(face);
    if (!geometry.is_cut(cell) && !geometry.is_cut(neighbor))
      return {};
    const std::vector<unsigned int> here  = fields_on(cell),
                                    there = fields_on(neighbor);
    std::vector<unsigned int> both;
    std::set_intersection(here.begin(),
                          here.end(),
                          there.begin(),
                          there.end(),
                          std::back_inserter(both));
    return both;
  }

  template <typename Function>
  void
  CutCellProblem::for_each_ghost_penalty_face(const Function &f) const
  {
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        for (const unsigned int face : cell->face_indices())
          if (!ghost_penalty_fields(cell, face).empty() &&
              (cell->neighbor_is_coarser(face) ||
               cell->id() < cell->neighbor(face)->id()))
            f(cell, face);
  }

  void
  CutCellProblem::set_up_matrix()
  {
    TimerOutput::Scope scope(timer, "diffusion: sparsity");
    // A constrained node of a ghost cell can hang on nodes this rank does not
    // see: the rows it writes are those too.
    IndexSet written_rows = relevant_dofs;
    for (const auto &line : constraints.get_lines())
      for (const auto &[dof, weight] : line.entries)
        written_rows.add_index(dof);
    written_rows.compress();
    DynamicSparsityPattern pattern(written_rows);
    DoFTools::make_sparsity_pattern(dof_handler, pattern, constraints, false);
    // The ghost penalty couples the DoFs of the two cells of its faces.
    std::vector<types::global_dof_index> dofs, neighbor_dofs;
    for_each_ghost_penalty_face([&](const auto &cell, const unsigned int face) {
      dofs.resize(cell->get_fe().n_dofs_per_cell());
      cell->get_dof_indices(dofs);
      neighbor_dofs.resize(dofs.size());
      cell->neighbor(face)->get_dof_indices(neighbor_dofs);
      dofs.insert(dofs.end(), neighbor_dofs.begin(), neighbor_dofs.end());
      constraints.add_entries_local_to_global(dofs, pattern, false);
    });
    SparsityTools::distribute_sparsity_pattern(pattern,
                                               owned_dofs,
                                               communicator,
                                               written_rows);
    matrix.reinit(owned_dofs, owned_dofs, pattern, communicator);
    rhs.reinit(owned_dofs, communicator);
    solution.reinit(owned_dofs, relevant_dofs, communicator);
  }

  double
  CutCellProblem::field_permeability(
    const unsigned int,
    const DoFHandler<3>::active_cell_iterator &cell) const
  {
    return permeability(cell->material_id());
  }

  double
  CutCellProblem::nitsche_weight(
    const DoFHandler<3>::active_cell_iterator &cell) const
  {
    const unsigned int k = parameters.degree;
    return parameters.nitsche_penalty * k * (k + 1) /
           cell->minimum_vertex_distance();
  }

  void
  CutCellProblem::assemble()
  {
    assemble_operator();
    build_preconditioner();
  }

  void
  CutCellProblem::assemble_operator()
  {
    TimerOutput::Scope scope(timer, "diffusion: assemble");
    matrix = 0.;
    rhs    = 0.;
    assemble_cells();
    assemble_ghost_penalty();
    matrix.compress(VectorOperation::add);
    rhs.compress(VectorOperation::add);
    hold_unsupported_dofs();
  }

  void
  CutCellProblem::build_preconditioner()
  {
    TimerOutput::Scope scope(timer, "diffusion: AMG setup");
    initialize_uptake_amg(amg, matrix, parameters.degree);
  }

  void
  CutCellProblem::hold_unsupported_dofs()
  {
    // A field can reach into a mesh cell as a sliver of round-off measure
    // (seen at a folded rim, the regression case folded_rim), and if no
    // ghost penalty face reaches its DoFs either, their rows are round-off
    // of either sign, which the diagonal scaling in solve() would divide
    // by: hold them at zero, as the unused fields' DoFs are.
    const Epetra_CrsMatrix &rows    = matrix.trilinos_matrix();
    double                  largest = 0.;
    for (const auto i : owned_dofs)
      largest = std::max(largest, std::abs(matrix.diag_element(i)));
    largest = Utilities::MPI::max(largest, communicator);
    for (int r = 0; r < rows.NumMyRows(); ++r)
      {
        int     n;
        double *values;
        int    *columns;
        rows.ExtractMyRowView(r, n, values, columns);
        double row = 0.;
        for (int k = 0; k < n; ++k)
          row = std::max(row, std::abs(values[k]));
        if (row < 1e-12 * largest)
          {
            const types::global_dof_index i =
              TrilinosWrappers::global_row_index(rows, r);
            matrix.set(i, i, largest);
            rhs[i] = 0.;
          }
      }
    matrix.compress(VectorOperation::insert);
    rhs.compress(VectorOperation::insert);
  }

  CutCellShapes
  CutCellProblem::shapes_on(
    const DoFHandler<3>::active_cell_iterator &cell) const
  {
    // Field 0 is the plasma's, 1 + c the inside of the red cells of
    // colour c: on a mesh cell the shape functions of the plasma's field
    // are on side 0, those of the red cell it reaches into on side 1.
    const FiniteElement<3>         &fe     = fe_collection[ActiveFE::fields];
    const std::vector<unsigned int> fields = pressure_fields_on(cell);
    CutCellShapes                   shapes;
    for (unsigned int i = 0; i < fe.n_dofs_per_cell(); ++i)
      {
        const unsigned int field = fe.system_to_component_index(i).first;
        shapes.side.push_back(field == 0 ? 0 : field == fields.back() ? 1 : -1);
        shapes.jump_sign.push_back(field == 0 ? 1. : -1.);
      }
    return shapes;
  }

  void
  CutCellProblem::for_each_field_cell(
    const NonMatching::RegionUpdateFlags &flags,
    const std::function<void(const NonMatching::FEValues<3> &,
                             const DoFHandler<3>::active_cell_iterator &)> &f)
    const
  {
    const auto values = geometry.cut_cell_values(fe_collection, flags);
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned() &&
          cell->active_fe_index() == ActiveFE::fields)
        {
          values->reinit(cell);
          f(*values, cell);
        }
  }

  void
  CutCellProblem::assemble_cells()
  {
    const unsigned int n = fe_collection[ActiveFE::fields].n_dofs_per_cell();
    FullMatrix<double> cell_matrix(n, n);
    Vector<double>     cell_rhs(n);
    std::vector<types::global_dof_index> dofs(n);
    for_each_field_cell(assembly_flags(),
                        [&](const NonMatching::FEValues<3>            &values,
                            const DoFHandler<3>::active_cell_iterator &cell) {
                          cell_matrix = 0.;
                          add_cell_terms(values,
                                         cell,
                                         shapes_on(cell),
                                         cell_matrix);
                          cell->get_dof_indices(dofs);
                          cell_rhs = 0.;
                          constraints.distribute_local_to_global(
                            cell_matrix, cell_rhs, dofs, matrix, rhs);
                        });
  }

  void
  CutCellProblem::assemble_ghost_penalty()
  {
    const unsigned int                   k = parameters.degree;
    const QGauss<2>                      quadrature(k + 1);
    FEInterfaceValues<3>                 interface_values(geometry.mapping(),
                                          fe_collection[ActiveFE::fields],
                                          quadrature,
                                          update_gradients | update_hessians |
                                            update_JxW_values |
                                            update_normal_vectors);
    FullMatrix<double>                   local;
    Vector<double>                       local_rhs;
    std::vector<types::global_dof_index> dofs;
    for_each_ghost_penalty_face([&](const auto &cell, const unsigned int face) {
      const auto neighbor = cell->neighbor(face);
      if (cell->neighbor_is_coarser(face))
        {
          const auto [neighbor_face, neighbor_subface] =
            cell->neighbor_of_coarser_neighbor(face);
          interface_values.reinit(cell,
                                  face,
                                  numbers::invalid_unsigned_int,
                                  neighbor,
                                  neighbor_face,
                                  neighbor_subface);
        }
      else
        interface_values.reinit(cell,
                                face,
                                numbers::invalid_unsigned_int,
                                neighbor,
                                cell->neighbor_of_neighbor(face),
                                numbers::invalid_unsigned_int);
      const unsigned int n = interface_values.n_current_interface_dofs();
      local.reinit(n, n);
      for (const unsigned int f : ghost_penalty_fields(cell, face))
        add_ghost_penalty(interface_values,
                          f,
                          parameters.ghost_penalty *
                            field_permeability(f, cell),
                          cell->minimum_vertex_distance(),
                          k,
                          local);
      dofs = interface_values.get_interface_dof_indices();
      local_rhs.reinit(n);
      constraints.distribute_local_to_global(
        local, local_rhs, dofs, matrix, rhs);
    });
  }

  void
  CutCellProblem::solve()
  {
    TimerOutput::Scope            scope(timer, "diffusion: solve");
    TrilinosWrappers::MPI::Vector x;
    SolverControl                 control(parameters.max_linear_iterations,
                          parameters.linear_tolerance);
    try
      {
        solve_scaled_cg(matrix, amg, owned_dofs, rhs, x, control);
      }
    catch (const SolverControl::NoConvergence &e)
      {
        throw no_convergence("CO diffusion (cut cells): CG",
                             e,
                             control.tolerance(),
                             "Raise Diffusion/Max linear iterations, or "
                             "Diffusion/Ghost penalty.");
      }
    iterations = control.last_step();
    if (!std::isfinite(x.l2_norm()))
      throw SolverFailure("CO diffusion: the solution is not finite.");
    constraints.distribute(x);
    solution = x;
    compute_flows();
  }

  void
  CutCellProblem::compute_flows()
  {
    NonMatching::RegionUpdateFlags flags;
    flags.surface = update_values | update_gradients | update_JxW_values |
                    update_normal_vectors;
    const auto fe_values_ptr = geometry.cut_cell_values(fe_collection, flags);
    NonMatching::FEValues<3> &fe_values = *fe_values_ptr;
    const MembraneSurfaces   &membranes = geometry.membranes();
    const FE_Q<2, 3>          flux_fe(1);
    flux_dof_handlers.clear();
    projections.resize(membranes.size());
    for (unsigned int m = 0; m < membranes.size(); ++m)
      {
        flux_dof_handlers.push_back(
          std::make_unique<DoFHandler<2, 3>>(*membranes.meshes()[m]));
        flux_dof_handlers.back()->distribute_dofs(flux_fe);
        projections[m].reinit(flux_dof_handlers.back()->n_dofs());
      }

    // j at each surface point, to its membrane: its flow and the integrals
    // ∫ j μ_i of the flux map.
    std::vector<types::global_dof_index> flux_dofs(flux_fe.n_dofs_per_cell());
    flows.assign(membranes.size(), 0.);
    for (const auto &cell : dof_handler.active_cell_iterators())
      {
        const auto found =
          geometry.surface_points().find(cell->active_cell_index());
        if (found == geometry.surface_points().end())
          continue;
        fe_values.reinit(cell);
        const auto &surface = *fe_values.get_surface_fe_values();
        const CutCellGeometry::SurfacePoints &points = found->second;
        AssertDimension(surface.n_quadrature_points, points.size());
        const std::vector<double> j = membrane_flux(surface, cell);
        for (const unsigned int q : surface.quadrature_point_indices())
          {
            const MembraneDistance::ClosestPoint &point = points[q];
            flows[point.membrane] += j[q] * surface.JxW(q);
            const DoFHandler<2, 3>::active_cell_iterator membrane_cell(
              membranes.meshes()[point.membrane],
              point.cell->level(),
              point.cell->index(),
              flux_dof_handlers[point.membrane].get());
            membrane_cell->get_dof_indices(flux_dofs);
            for (unsigned int i = 0; i < flux_dofs.size(); ++i)
              projections[point.membrane][flux_dofs[i]] +=
                j[q] * flux_fe.shape_value(i, point.reference) * surface.JxW(q);
          }
      }
    Utilities::MPI::sum(flows, communicator, flows);
    alveolar_flow = flow_through_boundary(dof_handler,
                                          geometry.mapping(),
                                          solution,
                                          pressure_boundary,
                                          permeability,
                                          communicator);
  }

  std::vector<double>
  CutCellProblem::membrane_flux(
    const NonMatching::FEImmersedSurfaceValues<3> &surface,
    const DoFHandler<3>::active_cell_iterator     &cell) const
  {
    // j = −{αD ∂ₙP} + β [P] (P₁ = 0 and {αD ∂ₙP} = αD ∂ₙP₀ for the membrane
    // sink), from jump: [P], and flux: w₀ αD ∇P₀ + w₁ α_cD_c ∇P₁.
    const unsigned int     n        = surface.n_quadrature_points;
    const MembraneCoupling coupling = membrane_coupling(cell);
    const double flux_weight[2] = {coupling.plasma_flux, coupling.cell_flux};
    std::vector<double>       jump(n, 0.), values(n);
    std::vector<Tensor<1, 3>> flux(n), gradients(n);
    for (const unsigned int f : pressure_fields_on(cell))
      {
        const FEValuesExtractors::Scalar field(f);
        surface[field].get_function_values(solution, values);
        surface[field].get_function_gradients(solution, gradients);
        for (unsigned int q = 0; q < n; ++q)
          {
            jump[q] += (f == 0 ? 1. : -1.) * values[q];
            flux[q] += flux_weight[f == 0 ? 0 : 1] * gradients[q];
          }
      }
    std::vector<double> j(n);
    for (unsigned int q = 0; q < n; ++q)
      j[q] = -(flux[q] * surface.normal_vector(q)) + coupling.penalty * jump[q];
    return j;
  }

  std::vector<Vector<double>>
  CutCellProblem::flux_map() const
  {
    // Every membrane's integrals in one sum over the ranks: one collective
    // per output, however many the membranes.
    std::vector<double> packed;
    for (const Vector<double> &projected : projections)
      packed.insert(packed.end(), projected.begin(), projected.end());
    Utilities::MPI::sum(packed, communicator, packed);

    // j_i = ∫ j μ_i / ∫ μ_i on the membrane.
    const MembraneSurfaces              &membranes = geometry.membranes();
    const FE_Q<2, 3>                     flux_fe(1);
    const QGauss<2>                      quadrature(3);
    FEValues<2, 3>                       membrane_values(membranes.mapping(),
                                   flux_fe,
                                   quadrature,
                                   update_values | update_JxW_values);
    std::vector<types::global_dof_index> dofs(flux_fe.n_dofs_per_cell());
    std::vector<Vector<double>>          map(membranes.size());
    auto                                 summed = packed.begin();
    for (unsigned int m = 0; m < membranes.size(); ++m)
      {
        Vector<double> mass(projections[m].size());
        for (const auto &cell : flux_dof_handlers[m]->active_cell_iterators())
          {
            membrane_values.reinit(cell);
            cell->get_dof_indices(dofs);
            for (const unsigned int q :
                 membrane_values.quadrature_point_indices())
              for (unsigned int i = 0; i < dofs.size(); ++i)
                mass[dofs[i]] +=
                  membrane_values.shape_value(i, q) * membrane_values.JxW(q);
          }
        map[m].reinit(mass.size());
        for (unsigned int i = 0; i < mass.size(); ++i)
          map[m][i] = *summed++ / mass[i];
      }
    return map;
  }

  types::global_dof_index
  CutCellProblem::n_dofs() const
  {
    return dof_handler.n_dofs() - n_unused_dofs;
  }

  std::vector<unsigned int>
  CutCellProblem::plasma_and_cell_fields(
    const Triangulation<3>::cell_iterator &cell) const
  {
    const NonMatching::LocationToLevelSet location = geometry.location(cell);
    std::vector<unsigned int>             fields;
    if (location != NonMatching::LocationToLevelSet::outside)
      fields.push_back(0);
    if (location != NonMatching::LocationToLevelSet::inside)
      fields.push_back(1 + geometry.colour(geometry.inside_of(cell)));
    return fields;
  }

  std::string
  CutCellProblem::flux_name() const
  {
    return "co_flux";
  }

  std::vector<unsigned int>
  CutCellProblem::pressure_fields_on(
    const Triangulation<3>::cell_iterator &cell) const
  {
    return fields_on(cell);
  }

  void
  CutCellProblem::add_pressure_fields(DataOut<3> &data_out) const
  {
    data_out.add_data_vector(solution, "co_pressure");
  }

  CutCellProblem::OutputFiles
  CutCellProblem::write_output(const std::string &directory,
                               const std::string &name,
                               const unsigned int counter,
                               const FieldData   &field_data) const
  {
    TimerOutput::Scope                    scope(timer, "diffusion: output");
    const parallel::TriangulationBase<3> &mesh = geometry.mesh();
    Vector<float>                         material_id(mesh.n_active_cells());
    for (const auto &cell : mesh.active_cell_iterators())
      material_id[cell->active_cell_index()] = cell->material_id();
    LinearAlgebra::distributed::Vector<double> membrane_distance(
      geometry.level_set());
    membrane_distance.zero_out_ghost_values();
    membrane_distance *= -1.;
    membrane_distance.update_ghost_values();

    DataOut<3> data_out;
    data_out.set_cell_selection(
      [this](const typename Triangulation<3>::cell_iterator &cell) {
        return cell->is_active() && cell->is_locally_owned() &&
               !fields_on(cell).empty();
      });
    data_out.set_flags(fast_vtk_flags());
    data_out.attach_dof_handler(dof_handler);
    add_pressure_fields(data_out);
    data_out.add_data_vector(geometry.level_set_dof_handler(),
                             membrane_distance,
                             "membrane_distance");
    data_out.add_data_vector(material_id,
                             "material_id",
                             DataOut<3>::type_cell_data);
    data_out.build_patches(geometry.mapping(), parameters.degree);
    const MembraneSurfaces &membranes = geometry.membranes();
    return write_fields(data_out,
                        membranes.meshes(),
                        membranes.mapping(),
                        flux_dof_handlers,
                        flux_map(),
                        directory,
                        name,
                        counter,
                        communicator,
                        field_data,
                        flux_name());
  }
} // namespace rbc_ifem
