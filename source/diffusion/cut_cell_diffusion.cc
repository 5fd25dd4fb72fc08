#include <rbc_ifem/base/input_error.h>
#include <rbc_ifem/base/output.h>
#include <rbc_ifem/base/solver_failure.h>
#include <rbc_ifem/diffusion/cut_cell_diffusion.h>
#include <rbc_ifem/diffusion/diagonally_scaled.h>
#include <rbc_ifem/geometry/capillary_mesh.h>

#include <deal.II/base/function.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_interface_values.h>
#include <deal.II/fe/fe_nothing.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/hp/mapping_collection.h>
#include <deal.II/hp/q_collection.h>
#include <deal.II/lac/solver_cg.h>
#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/trilinos_sparsity_pattern.h>
#include <deal.II/non_matching/fe_values.h>
#include <deal.II/numerics/data_out.h>
#include <deal.II/numerics/vector_tools.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <sstream>

namespace rbc_ifem
{
  namespace
  {
    /// The two elements of the hp collection.
    enum ActiveFE : unsigned int
    {
      lagrange = 0, ///< cells that reach into the plasma
      nothing  = 1  ///< cells wholly inside a red cell
    };

    /// What every rank of @p communicator has in @p local, in rank order.
    template <typename T>
    std::vector<T>
    gather(const std::vector<T> &local, const MPI_Comm communicator)
    {
      std::vector<T> all;
      for (const auto &found : Utilities::MPI::all_gather(communicator, local))
        all.insert(all.end(), found.begin(), found.end());
      return all;
    }

    bool
    is_cut(const NonMatching::MeshClassifier<3>           &classifier,
           const typename Triangulation<3>::cell_iterator &cell)
    {
      return classifier.location_to_level_set(cell) ==
             NonMatching::LocationToLevelSet::intersected;
    }
  } // namespace

  UnresolvedCutCells::UnresolvedCutCells(
    std::vector<CellId>                                         cells,
    const std::optional<std::pair<unsigned int, unsigned int>> &membranes)
    : std::runtime_error("cut cells that the level set cannot resolve")
    , cells(std::move(cells))
    , membranes(membranes)
  {}

  CutCellDiffusion::CutCellDiffusion(
    const DiffusionParameters                 &parameters,
    const std::function<double(unsigned int)> &permeability,
    const types::boundary_id                   pressure_boundary,
    const MPI_Comm                             communicator,
    TimerOutput                               &timer,
    const std::optional<double>               &period)
    : DiffusionSolver(parameters.alveolar_pressure)
    , parameters(parameters)
    , permeability(permeability)
    , pressure_boundary(pressure_boundary)
    , period(period)
    , communicator(communicator)
    , timer(timer)
    , mapping(parameters.degree)
    , mapping_collection(mapping)
    , cell_quadrature(QGauss<3>(parameters.degree + 1))
    , line_quadrature(QGauss<1>(parameters.degree + 1))
    , level_set_fe(parameters.degree)
  {
    fe_collection.push_back(FE_Q<3>(parameters.degree));
    fe_collection.push_back(FE_Nothing<3>());
  }

  CutCellDiffusion::~CutCellDiffusion()
  {
    // The DoFHandlers refer to the mesh and the classifier to the level set
    // DoFHandler: release them first.
    classifier.reset();
    dof_handler.clear();
    level_set_dof_handler.clear();
  }

  void
  CutCellDiffusion::setup(
    const parallel::TriangulationBase<3>           &mesh,
    const std::vector<const Triangulation<2, 3> *> &membranes,
    const MappingQ<2, 3>                           &membrane_mapping)
  {
    TimerOutput::Scope scope(timer, "diffusion: setup");
    this->mesh             = &mesh;
    this->membranes        = membranes;
    this->membrane_mapping = &membrane_mapping;
    if (shared_distance)
      distance = shared_distance;
    else
      {
        TimerOutput::Scope sampling(timer, "diffusion: membrane sampling");
        distance = std::make_shared<MembraneDistance>(membranes,
                                                      membrane_mapping,
                                                      period);
      }
    compute_level_set();
    // Both kinds of unresolved cells at once, so that one refinement takes
    // care of them; one membrane shares no cell, and the surface points of a
    // mesh that will be refined are not needed.
    const std::vector<CellId> ridges =
      ridge_refinement ? ridge_cells() : std::vector<CellId>();
    if (membranes.size() == 1 &&
        Utilities::MPI::logical_or(!ridges.empty(), communicator))
      throw_if_unresolved(ridges, SharedCells());
    const SharedCells shared = locate_surface_points();
    throw_if_unresolved(ridges, shared);
    {
      TimerOutput::Scope dofs_scope(timer, "diffusion: DoFs and constraints");
      distribute_dofs();
      make_pressure_constraints(dof_handler,
                                mapping,
                                pressure_boundary,
                                parameters.alveolar_pressure,
                                period,
                                constraints);
    }
    setup_matrix();
  }

  void
  CutCellDiffusion::compute_level_set()
  {
    TimerOutput::Scope scope(timer, "diffusion: level set");
    level_set_dof_handler.reinit(*mesh);
    level_set_dof_handler.distribute_dofs(level_set_fe);
    const IndexSet owned = level_set_dof_handler.locally_owned_dofs();
    IndexSet       relevant;
    DoFTools::extract_locally_relevant_dofs(level_set_dof_handler, relevant);

    // Every node of an owned cell is computed here, those other ranks own
    // too: the ridge check needs their closest points.
    LinearAlgebra::distributed::Vector<double> owned_values(owned,
                                                            communicator);
    closest_points.clear();
    for (const auto &[dof, position] : level_set_nodes())
      {
        const MembraneDistance::ClosestPoint closest =
          distance->closest_point(position);
        if (owned.is_element(dof))
          owned_values[dof] = -closest.signed_distance;
        closest_points.emplace(dof, closest);
      }
    // Hanging values take the coarse side's, so that neighbours agree on
    // where the membrane is.
    AffineConstraints<double> hanging(relevant);
    DoFTools::make_hanging_node_constraints(level_set_dof_handler, hanging);
    hanging.close();
    hanging.distribute(owned_values);
    level_set.reinit(owned, relevant, communicator);
    for (const auto dof : owned)
      level_set[dof] = owned_values[dof];
    level_set.update_ghost_values();

    classifier =
      std::make_unique<NonMatching::MeshClassifier<3>>(level_set_dof_handler,
                                                       level_set);
    classifier->reclassify();
  }

  std::vector<std::pair<types::global_dof_index, Point<3>>>
  CutCellDiffusion::level_set_nodes() const
  {
    // Every cell that holds a node of an owned cell shares a vertex with
    // it, so it is owned or a ghost here.
    std::map<types::global_dof_index, std::pair<CellId, Point<3>>> placed;
    std::set<types::global_dof_index>                              wanted;
    FEValues<3>                          fe_values(mapping,
                          level_set_fe,
                          Quadrature<3>(level_set_fe.get_unit_support_points()),
                          update_quadrature_points);
    std::vector<types::global_dof_index> dofs(level_set_fe.n_dofs_per_cell());
    for (const auto &cell : level_set_dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          cell->get_dof_indices(dofs);
          wanted.insert(dofs.begin(), dofs.end());
        }
    for (const auto &cell : level_set_dof_handler.active_cell_iterators())
      if (!cell->is_artificial())
        {
          cell->get_dof_indices(dofs);
          bool evaluated = false;
          for (unsigned int i = 0; i < dofs.size(); ++i)
            if (wanted.count(dofs[i]) > 0)
              {
                const auto found = placed.find(dofs[i]);
                if (found != placed.end() && found->second.first < cell->id())
                  continue;
                if (!evaluated)
                  fe_values.reinit(cell);
                evaluated       = true;
                placed[dofs[i]] = {cell->id(), fe_values.quadrature_point(i)};
              }
        }
    std::vector<std::pair<types::global_dof_index, Point<3>>> nodes;
    nodes.reserve(placed.size());
    for (const auto &[dof, placement] : placed)
      nodes.emplace_back(dof, placement.second);
    return nodes;
  }

  void
  CutCellDiffusion::refine_ridges(const bool refine)
  {
    ridge_refinement = refine;
  }

  void
  CutCellDiffusion::share_membrane_distance(
    std::shared_ptr<const MembraneDistance> distance)
  {
    shared_distance = std::move(distance);
  }

  std::vector<CellId>
  CutCellDiffusion::ridge_cells() const
  {
    std::vector<CellId>                  cells;
    std::vector<types::global_dof_index> dofs(level_set_fe.n_dofs_per_cell());
    for (const auto &cell : level_set_dof_handler.active_cell_iterators())
      if (cell->is_locally_owned() && is_cut(*classifier, cell))
        {
          cell->get_dof_indices(dofs);
          const auto faces_away = [&](const types::global_dof_index i) {
            const MembraneDistance::ClosestPoint &a = closest_points.at(i);
            return std::any_of(dofs.begin(), dofs.end(), [&](const auto j) {
              const MembraneDistance::ClosestPoint &b = closest_points.at(j);
              return a.membrane == b.membrane && a.normal * b.normal < 0.;
            });
          };
          if (std::any_of(dofs.begin(), dofs.end(), faces_away))
            cells.push_back(cell->id());
        }
    return cells;
  }

  void
  CutCellDiffusion::throw_if_unresolved(const std::vector<CellId> &ridges,
                                        const SharedCells         &shared) const
  {
    std::vector<CellId> cells = gather(shared.cells, communicator);
    std::optional<std::pair<unsigned int, unsigned int>> membranes;
    if (!cells.empty())
      // The pair from the lowest rank that found one.
      for (const auto &pair :
           Utilities::MPI::all_gather(communicator, shared.membranes))
        if (pair.first != pair.second)
          {
            membranes = pair;
            break;
          }
    const std::vector<CellId> ridge_cells = gather(ridges, communicator);
    cells.insert(cells.end(), ridge_cells.begin(), ridge_cells.end());
    if (!cells.empty())
      throw UnresolvedCutCells(cells, membranes);
  }

  void
  CutCellDiffusion::distribute_dofs()
  {
    dof_handler.reinit(*mesh);
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        cell->set_active_fe_index(classifier->location_to_level_set(cell) ==
                                      NonMatching::LocationToLevelSet::outside ?
                                    ActiveFE::nothing :
                                    ActiveFE::lagrange);
    dof_handler.distribute_dofs(fe_collection);
    owned_dofs = dof_handler.locally_owned_dofs();
    DoFTools::extract_locally_relevant_dofs(dof_handler, relevant_dofs);
  }


  CutCellDiffusion::SharedCells
  CutCellDiffusion::locate_surface_points()
  {
    TimerOutput::Scope             scope(timer, "diffusion: surface points");
    NonMatching::RegionUpdateFlags flags;
    flags.surface                           = update_quadrature_points;
    const auto                fe_values_ptr = cut_cell_values(flags);
    NonMatching::FEValues<3> &fe_values     = *fe_values_ptr;
    // What the membranes ask of the mesh, found on this rank's cut cells:
    // [0] a cut cell outside the plasma (a membrane in the vessel wall) and
    // [1 + m] the number of surface points on membrane m; and the cut cells
    // that two membranes share.
    std::vector<unsigned int> findings(1 + membranes.size(), 0);
    SharedCells               shared;
    surface_points.clear();
    for (const auto &cell : level_set_dof_handler.active_cell_iterators())
      if (cell->is_locally_owned() && is_cut(*classifier, cell))
        {
          fe_values.reinit(cell);
          const auto &surface = fe_values.get_surface_fe_values();
          if (!surface)
            continue;
          if (cell->material_id() != Material::plasma)
            findings[0] = 1;
          SurfacePoints &points = surface_points[cell->active_cell_index()];
          for (const auto &x : surface->get_quadrature_points())
            {
              points.push_back(distance->closest_point(x));
              ++findings[1 + points.back().membrane];
            }
          for (const auto &point : points)
            if (point.membrane != points.front().membrane)
              {
                shared.cells.push_back(cell->id());
                shared.membranes = {
                  std::min(point.membrane, points.front().membrane),
                  std::max(point.membrane, points.front().membrane)};
                break;
              }
        }
    Utilities::MPI::max(findings, communicator, findings);
    if (findings[0] > 0)
      throw InputError("Layout",
                       "a membrane in the vessel wall",
                       "a membrane reaches out of the lumen into the vessel "
                       "wall; every cell must lie inside the capillary.");
    for (unsigned int m = 0; m < membranes.size(); ++m)
      if (findings[1 + m] == 0)
        throw InputError("Layout",
                         "cell " + std::to_string(m),
                         "this membrane cuts no cell of the diffusion mesh: "
                         "it lies outside the capillary, or within one "
                         "cell of the mesh.");
    return shared;
  }

  bool
  CutCellDiffusion::face_has_ghost_penalty(
    const DoFHandler<3>::active_cell_iterator &cell,
    const unsigned int                         face) const
  {
    if (cell->at_boundary(face) || cell->active_fe_index() != lagrange)
      return false;
    const auto neighbor = cell->neighbor(face);
    if (neighbor->has_children() || neighbor->active_fe_index() != lagrange)
      return false;
    return is_cut(*classifier, cell) || is_cut(*classifier, neighbor);
  }

  template <typename Function>
  void
  CutCellDiffusion::for_each_ghost_penalty_face(const Function &f) const
  {
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        for (const unsigned int face : cell->face_indices())
          if (face_has_ghost_penalty(cell, face) &&
              (cell->neighbor_is_coarser(face) ||
               cell->id() < cell->neighbor(face)->id()))
            f(cell, face);
  }

  void
  CutCellDiffusion::setup_matrix()
  {
    TimerOutput::Scope scope(timer, "diffusion: sparsity");
    // A constrained node of a ghost cell can hang on nodes this rank does not
    // see: the rows it writes are those too.
    IndexSet written_rows = relevant_dofs;
    for (const auto &line : constraints.get_lines())
      for (const auto &[dof, weight] : line.entries)
        written_rows.add_index(dof);
    written_rows.compress();
    TrilinosWrappers::SparsityPattern pattern(owned_dofs,
                                              owned_dofs,
                                              written_rows,
                                              communicator);
    DoFTools::make_sparsity_pattern(dof_handler,
                                    pattern,
                                    constraints,
                                    false,
                                    Utilities::MPI::this_mpi_process(
                                      communicator));
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
    pattern.compress();
    matrix.reinit(pattern);
    rhs.reinit(owned_dofs, communicator);
    solution.reinit(owned_dofs, relevant_dofs, communicator);
  }

  std::unique_ptr<NonMatching::FEValues<3>>
  CutCellDiffusion::cut_cell_values(
    const NonMatching::RegionUpdateFlags &flags) const
  {
    return std::make_unique<NonMatching::FEValues<3>>(mapping_collection,
                                                      fe_collection,
                                                      cell_quadrature,
                                                      line_quadrature,
                                                      flags,
                                                      *classifier,
                                                      level_set_dof_handler,
                                                      level_set);
  }

  double
  CutCellDiffusion::nitsche_weight(
    const DoFHandler<3>::active_cell_iterator &cell) const
  {
    const unsigned int k = parameters.degree;
    return parameters.nitsche_penalty * k * (k + 1) *
           permeability(cell->material_id()) / cell->minimum_vertex_distance();
  }

  void
  CutCellDiffusion::assemble()
  {
    TimerOutput::Scope scope(timer, "diffusion: assemble");
    matrix = 0.;
    rhs    = 0.;
    assemble_cells();
    assemble_ghost_penalty();
    matrix.compress(VectorOperation::add);
    rhs.compress(VectorOperation::add);

    TimerOutput::Scope amg_scope(timer, "diffusion: AMG setup");
    TrilinosWrappers::PreconditionAMG::AdditionalData amg_data;
    amg_data.elliptic              = true;
    amg_data.higher_order_elements = parameters.degree > 1;
    amg_data.smoother_sweeps       = 2;
    amg_data.aggregation_threshold = 0.02;
    amg.initialize(matrix, amg_data);
  }

  void
  CutCellDiffusion::assemble_cells()
  {
    NonMatching::RegionUpdateFlags flags;
    flags.inside  = update_gradients | update_JxW_values;
    flags.surface = update_values | update_gradients | update_JxW_values |
                    update_normal_vectors;
    const auto                fe_values_ptr = cut_cell_values(flags);
    NonMatching::FEValues<3> &fe_values     = *fe_values_ptr;
    const unsigned int        n = fe_collection[lagrange].n_dofs_per_cell();
    FullMatrix<double>        cell_matrix(n, n);
    Vector<double>            cell_rhs(n);
    std::vector<types::global_dof_index> dofs(n);
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned() && cell->active_fe_index() == lagrange)
        {
          fe_values.reinit(cell);
          const double alpha_D = permeability(cell->material_id());
          cell_matrix          = 0.;
          if (const auto &inside = fe_values.get_inside_fe_values())
            for (const unsigned int q : inside->quadrature_point_indices())
              for (unsigned int i = 0; i < n; ++i)
                for (unsigned int j = 0; j < n; ++j)
                  cell_matrix(i, j) += alpha_D * inside->shape_grad(i, q) *
                                       inside->shape_grad(j, q) *
                                       inside->JxW(q);
          if (const auto &surface = fe_values.get_surface_fe_values())
            {
              // P = 0 on the membrane: the symmetric Nitsche terms.
              const double penalty = nitsche_weight(cell);
              for (const unsigned int q : surface->quadrature_point_indices())
                {
                  const Tensor<1, 3> &normal = surface->normal_vector(q);
                  for (unsigned int i = 0; i < n; ++i)
                    {
                      const double flux_i =
                        alpha_D * (normal * surface->shape_grad(i, q));
                      const double v_i = surface->shape_value(i, q);
                      for (unsigned int j = 0; j < n; ++j)
                        cell_matrix(i, j) +=
                          (-flux_i * surface->shape_value(j, q) -
                           alpha_D * (normal * surface->shape_grad(j, q)) *
                             v_i +
                           penalty * v_i * surface->shape_value(j, q)) *
                          surface->JxW(q);
                    }
                }
            }
          cell->get_dof_indices(dofs);
          cell_rhs = 0.;
          constraints.distribute_local_to_global(
            cell_matrix, cell_rhs, dofs, matrix, rhs);
        }
  }

  void
  CutCellDiffusion::assemble_ghost_penalty()
  {
    const unsigned int   k = parameters.degree;
    const QGauss<2>      quadrature(k + 1);
    FEInterfaceValues<3> interface_values(mapping,
                                          fe_collection[lagrange],
                                          quadrature,
                                          update_gradients | update_hessians |
                                            update_JxW_values |
                                            update_normal_vectors);
    FullMatrix<double>   local;
    Vector<double>       local_rhs;
    // n ≤ twice the DoFs of a cell.
    std::vector<double> first(2 * fe_collection[lagrange].n_dofs_per_cell()),
      second(first.size());
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
      // γ_g αD h^(2j-1) ([∂ₙʲP], [∂ₙʲq]) for j = 1 .. k (k <= 2 here: the
      // third derivatives of Q3 are not penalised).
      const double h = cell->minimum_vertex_distance();
      const double weight =
        parameters.ghost_penalty * permeability(cell->material_id());
      const unsigned int n = interface_values.n_current_interface_dofs();
      local.reinit(n, n);
      for (const unsigned int q : interface_values.quadrature_point_indices())
        {
          // The jumps of ∂ₙφ_i and ∂ₙₙφ_i, once per shape function.
          const Tensor<1, 3> &normal = interface_values.normal(q);
          for (unsigned int i = 0; i < n; ++i)
            {
              first[i] =
                normal * interface_values.jump_in_shape_gradients(i, q);
              second[i] =
                k > 1 ?
                  normal *
                    (interface_values.jump_in_shape_hessians(i, q) * normal) :
                  0.;
            }
          const double w1 = weight * h * interface_values.JxW(q);
          const double w2 = weight * h * h * h * interface_values.JxW(q);
          for (unsigned int i = 0; i < n; ++i)
            for (unsigned int j = 0; j < n; ++j)
              local(i, j) +=
                w1 * first[i] * first[j] + w2 * second[i] * second[j];
        }
      dofs = interface_values.get_interface_dof_indices();
      local_rhs.reinit(n);
      constraints.distribute_local_to_global(
        local, local_rhs, dofs, matrix, rhs);
    });
  }

  void
  CutCellDiffusion::solve()
  {
    TimerOutput::Scope scope(timer, "diffusion: solve");
    // D = diag(A)^-1/2: every row O(1) on the diagonal.
    TrilinosWrappers::MPI::Vector scale(rhs), inverse_scale(rhs);
    for (const auto i : owned_dofs)
      {
        scale[i]         = 1. / std::sqrt(matrix.diag_element(i));
        inverse_scale[i] = 1. / scale[i];
      }
    scale.compress(VectorOperation::insert);
    inverse_scale.compress(VectorOperation::insert);

    TrilinosWrappers::MPI::Vector scaled_rhs(rhs), x(rhs);
    scaled_rhs.scale(scale);
    x = 0.;
    SolverControl control(parameters.max_linear_iterations,
                          parameters.linear_tolerance * scaled_rhs.l2_norm());
    SolverCG<TrilinosWrappers::MPI::Vector> cg(control);
    try
      {
        cg.solve(
          DiagonallyScaled<TrilinosWrappers::SparseMatrix,
                           TrilinosWrappers::MPI::Vector>(matrix, scale),
          x,
          scaled_rhs,
          DiagonallyScaled<TrilinosWrappers::PreconditionAMG,
                           TrilinosWrappers::MPI::Vector>(amg, inverse_scale));
      }
    catch (const SolverControl::NoConvergence &e)
      {
        throw SolverFailure(
          "CO diffusion (cut cells): CG did not converge in " +
          std::to_string(e.last_step) + " iterations (residual " +
          Utilities::to_string(e.last_residual) + ", wanted " +
          Utilities::to_string(control.tolerance()) +
          "). Raise Diffusion/Max linear iterations, or Diffusion/Ghost "
          "penalty.");
      }
    x.scale(scale);
    iterations = control.last_step();
    if (!std::isfinite(x.l2_norm()))
      throw SolverFailure("CO diffusion: the solution is not finite.");
    constraints.distribute(x);
    solution = x;
    compute_flows();
  }

  void
  CutCellDiffusion::compute_flows()
  {
    NonMatching::RegionUpdateFlags flags;
    flags.surface = update_values | update_gradients | update_JxW_values |
                    update_normal_vectors;
    const auto                fe_values_ptr = cut_cell_values(flags);
    NonMatching::FEValues<3> &fe_values     = *fe_values_ptr;
    const FE_Q<2, 3>          flux_fe(1);
    flux_dof_handlers.clear();
    std::vector<Vector<double>> projected(membranes.size());
    for (unsigned int m = 0; m < membranes.size(); ++m)
      {
        flux_dof_handlers.push_back(
          std::make_unique<DoFHandler<2, 3>>(*membranes[m]));
        flux_dof_handlers.back()->distribute_dofs(flux_fe);
        projected[m].reinit(flux_dof_handlers.back()->n_dofs());
      }

    // j = -αD ∂ₙP + penalty P at each surface point, to its membrane.
    std::vector<double>                  values;
    std::vector<Tensor<1, 3>>            gradients;
    std::vector<types::global_dof_index> flux_dofs(flux_fe.n_dofs_per_cell());
    flows.assign(membranes.size(), 0.);
    for (const auto &cell : dof_handler.active_cell_iterators())
      {
        const auto found = surface_points.find(cell->active_cell_index());
        if (found == surface_points.end())
          continue;
        fe_values.reinit(cell);
        const auto          &surface = fe_values.get_surface_fe_values();
        const SurfacePoints &points  = found->second;
        AssertDimension(surface->n_quadrature_points, points.size());
        values.resize(points.size());
        gradients.resize(points.size());
        surface->get_function_values(solution, values);
        surface->get_function_gradients(solution, gradients);
        const double alpha_D = permeability(cell->material_id());
        const double penalty = nitsche_weight(cell);
        for (const unsigned int q : surface->quadrature_point_indices())
          {
            const double j =
              -alpha_D * (gradients[q] * surface->normal_vector(q)) +
              penalty * values[q];
            const MembraneDistance::ClosestPoint &point = points[q];
            flows[point.membrane] += j * surface->JxW(q);
            const DoFHandler<2, 3>::active_cell_iterator membrane_cell(
              membranes[point.membrane],
              point.cell->level(),
              point.cell->index(),
              flux_dof_handlers[point.membrane].get());
            membrane_cell->get_dof_indices(flux_dofs);
            for (unsigned int i = 0; i < flux_dofs.size(); ++i)
              projected[point.membrane][flux_dofs[i]] +=
                j * flux_fe.shape_value(i, point.reference) * surface->JxW(q);
          }
      }
    Utilities::MPI::sum(flows, communicator, flows);

    // The lumped L² projection: j_i = ∫ j μ_i / ∫ μ_i on the membrane.
    flux_map.resize(membranes.size());
    const QGauss<2> quadrature(3);
    FEValues<2, 3>  membrane_values(*membrane_mapping,
                                   flux_fe,
                                   quadrature,
                                   update_values | update_JxW_values);
    for (unsigned int m = 0; m < membranes.size(); ++m)
      {
        Utilities::MPI::sum(projected[m], communicator, projected[m]);
        Vector<double> mass(projected[m].size());
        for (const auto &cell : flux_dof_handlers[m]->active_cell_iterators())
          {
            membrane_values.reinit(cell);
            cell->get_dof_indices(flux_dofs);
            for (const unsigned int q :
                 membrane_values.quadrature_point_indices())
              for (unsigned int i = 0; i < flux_dofs.size(); ++i)
                mass[flux_dofs[i]] +=
                  membrane_values.shape_value(i, q) * membrane_values.JxW(q);
          }
        flux_map[m].reinit(mass.size());
        for (unsigned int i = 0; i < mass.size(); ++i)
          flux_map[m][i] = projected[m][i] / mass[i];
      }

    alveolar_flow = flow_through_boundary(dof_handler,
                                          mapping,
                                          solution,
                                          pressure_boundary,
                                          permeability,
                                          communicator);
  }

  types::global_dof_index
  CutCellDiffusion::n_dofs() const
  {
    return dof_handler.n_dofs();
  }

  CutCellDiffusion::OutputFiles
  CutCellDiffusion::write_output(const std::string &directory,
                                 const std::string &name,
                                 const unsigned int counter,
                                 const FieldData   &field_data) const
  {
    TimerOutput::Scope scope(timer, "diffusion: output");
    Vector<float>      material_id(mesh->n_active_cells());
    for (const auto &cell : mesh->active_cell_iterators())
      material_id[cell->active_cell_index()] = cell->material_id();
    LinearAlgebra::distributed::Vector<double> membrane_distance(level_set);
    membrane_distance.zero_out_ghost_values();
    membrane_distance *= -1.;
    membrane_distance.update_ghost_values();

    DataOut<3> data_out;
    data_out.set_cell_selection(
      [this](const typename Triangulation<3>::cell_iterator &cell) {
        return cell->is_active() && cell->is_locally_owned() &&
               classifier->location_to_level_set(cell) !=
                 NonMatching::LocationToLevelSet::outside;
      });
    data_out.set_flags(fast_vtk_flags());
    data_out.attach_dof_handler(dof_handler);
    data_out.add_data_vector(solution, "co_pressure");
    data_out.add_data_vector(level_set_dof_handler,
                             membrane_distance,
                             "membrane_distance");
    data_out.add_data_vector(material_id,
                             "material_id",
                             DataOut<3>::type_cell_data);
    data_out.build_patches(mapping, parameters.degree);
    return write_fields(data_out,
                        membranes,
                        *membrane_mapping,
                        flux_dof_handlers,
                        flux_map,
                        directory,
                        name,
                        counter,
                        communicator,
                        field_data);
  }
} // namespace rbc_ifem
