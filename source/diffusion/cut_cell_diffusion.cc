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
#include <deal.II/fe/fe_system.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/hp/mapping_collection.h>
#include <deal.II/hp/q_collection.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/solver_cg.h>
#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/sparsity_tools.h>
#include <deal.II/lac/trilinos_index_access.h>
#include <deal.II/non_matching/fe_values.h>
#include <deal.II/numerics/data_out.h>
#include <deal.II/numerics/data_postprocessor.h>
#include <deal.II/numerics/vector_tools.h>

#include <Epetra_MultiVector.h>
#include <Teuchos_ParameterList.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
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

    /// MappingQ, with the placement of a cell's support points public, so
    /// that a MappingQCache can be filled for some cells only.
    struct SupportPointsOfMappingQ : public MappingQ<3>
    {
      using MappingQ<3>::MappingQ;
      using MappingQ<3>::compute_mapping_support_points;
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

    /**
     * One side's P with a reaction: on each mesh cell the field that
     * @p field_on gives (numbers::invalid_unsigned_int: 0, the mesh cell is
     * wholly on the other side).
     */
    class SideField : public DataPostprocessorScalar<3>
    {
    public:
      SideField(
        const std::string &name,
        std::function<unsigned int(const DoFHandler<3>::cell_iterator &)>
          field_on)
        : DataPostprocessorScalar<3>(name, update_values)
        , field_on(std::move(field_on))
      {}

      void
      evaluate_vector_field(
        const DataPostprocessorInputs::Vector<3> &inputs,
        std::vector<Vector<double>>              &computed) const override
      {
        const unsigned int field = field_on(inputs.template get_cell<3>());
        for (unsigned int q = 0; q < computed.size(); ++q)
          computed[q](0) = field == numbers::invalid_unsigned_int ?
                             0. :
                             inputs.solution_values[q](field);
      }

    private:
      const std::function<unsigned int(const DoFHandler<3>::cell_iterator &)>
        field_on;
    };

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
  CutCellDiffusion::react_inside_cells(const double cell_permeability,
                                       const double rate)
  {
    reaction = CellReaction{cell_permeability, rate};
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
    cache_mapping();
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
    SharedCells shared = locate_surface_points();
    if (separate_cells || reaction)
      add_gap_cells(shared);
    throw_if_unresolved(ridges, shared);
    if (reaction)
      {
        find_cell_membranes();
        colour_membranes();
      }
    {
      TimerOutput::Scope dofs_scope(timer, "diffusion: DoFs and constraints");
      distribute_dofs();
      const IndexSet unused = unused_field_dofs();
      n_unused_dofs =
        Utilities::MPI::sum((unused & owned_dofs).n_elements(), communicator);
      make_pressure_constraints(dof_handler,
                                mapping,
                                pressure_boundary,
                                parameters.alveolar_pressure,
                                period,
                                constraints,
                                unused);
    }
    setup_matrix();
  }

  void
  CutCellDiffusion::cache_mapping()
  {
    const SupportPointsOfMappingQ exact(parameters.degree);
    const unsigned int n_points = Utilities::pow(parameters.degree + 1, 3);
    mapping.initialize(*mesh, [&](const Triangulation<3>::cell_iterator &cell) {
      // Nothing here evaluates on a parent or an artificial cell: they keep
      // a placeholder, and cost nothing.
      if (cell->is_active() && !cell->is_artificial())
        return exact.compute_mapping_support_points(cell);
      return std::vector<Point<3>>(n_points, cell->vertex(0));
    });
    // The collection holds a copy, which shares the cache just made.
    mapping_collection = hp::MappingCollection<3>(mapping);
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
  CutCellDiffusion::separate_insides(const bool separate)
  {
    separate_cells = separate;
  }

  void
  CutCellDiffusion::add_gap_cells(SharedCells &shared) const
  {
    std::vector<types::global_dof_index> dofs(level_set_fe.n_dofs_per_cell());
    for (const auto &cell : level_set_dof_handler.active_cell_iterators())
      if (cell->is_locally_owned() && is_cut(*classifier, cell))
        {
          cell->get_dof_indices(dofs);
          const unsigned int first = closest_points.at(dofs[0]).membrane;
          for (const auto dof : dofs)
            if (const unsigned int other = closest_points.at(dof).membrane;
                other != first)
              {
                shared.cells.push_back(cell->id());
                shared.membranes = {std::min(first, other),
                                    std::max(first, other)};
                break;
              }
        }
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
        cell->set_active_fe_index(fields_on(cell).empty() ? ActiveFE::nothing :
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

  std::vector<unsigned int>
  CutCellDiffusion::fields_on(const Triangulation<3>::cell_iterator &cell) const
  {
    const NonMatching::LocationToLevelSet location =
      classifier->location_to_level_set(cell);
    std::vector<unsigned int> fields;
    if (location != NonMatching::LocationToLevelSet::outside)
      fields.push_back(0);
    if (reaction && location != NonMatching::LocationToLevelSet::inside)
      fields.push_back(
        1 + membrane_colour[cell_membrane[cell->active_cell_index()]]);
    return fields;
  }

  void
  CutCellDiffusion::find_cell_membranes()
  {
    // The level set node deepest inside a red cell is closer to its
    // membrane than to any other: the straight line to another crosses it.
    cell_membrane.assign(mesh->n_active_cells(), numbers::invalid_unsigned_int);
    FEValues<3>                          nodes(mapping,
                      level_set_fe,
                      Quadrature<3>(level_set_fe.get_unit_support_points()),
                      update_quadrature_points);
    std::vector<types::global_dof_index> dofs(level_set_fe.n_dofs_per_cell());
    for (const auto &cell : level_set_dof_handler.active_cell_iterators())
      if (!cell->is_artificial() && classifier->location_to_level_set(cell) !=
                                      NonMatching::LocationToLevelSet::inside)
        {
          cell->get_dof_indices(dofs);
          const auto deepest =
            std::max_element(dofs.begin(), dofs.end(), [&](auto a, auto b) {
              return level_set[a] < level_set[b];
            });
          nodes.reinit(cell);
          cell_membrane[cell->active_cell_index()] =
            distance
              ->closest_point(
                nodes.quadrature_point(std::distance(dofs.begin(), deepest)))
              .membrane;
        }
  }

  void
  CutCellDiffusion::colour_membranes()
  {
    // Each membrane's box around the mesh cells that reach into it.
    const unsigned int  n = membranes.size();
    std::vector<double> lower(3 * n, std::numeric_limits<double>::max()),
      upper(3 * n, std::numeric_limits<double>::lowest());
    for (const auto &cell : mesh->active_cell_iterators())
      if (cell->is_locally_owned() &&
          cell_membrane[cell->active_cell_index()] !=
            numbers::invalid_unsigned_int)
        {
          const unsigned int m = cell_membrane[cell->active_cell_index()];
          for (const unsigned int v : cell->vertex_indices())
            for (unsigned int d = 0; d < 3; ++d)
              {
                lower[3 * m + d] =
                  std::min(lower[3 * m + d], cell->vertex(v)[d]);
                upper[3 * m + d] =
                  std::max(upper[3 * m + d], cell->vertex(v)[d]);
              }
        }
    Utilities::MPI::min(lower, communicator, lower);
    Utilities::MPI::max(upper, communicator, upper);
    // Boxes that touch (shifted by a period along x too) share mesh
    // vertices or faces, or may: their membranes get different colours.
    const auto touch = [&](const unsigned int a, const unsigned int b) {
      const double tolerance = 1e-8 * (upper[0] - lower[0] + 1.);
      for (const double shift : period ?
                                  std::vector<double>{0., *period, -*period} :
                                  std::vector<double>{0.})
        {
          bool overlap = true;
          for (unsigned int d = 0; d < 3; ++d)
            {
              const double s = d == 0 ? shift : 0.;
              overlap        = overlap &&
                        lower[3 * a + d] <= upper[3 * b + d] + s + tolerance &&
                        lower[3 * b + d] + s <= upper[3 * a + d] + tolerance;
            }
          if (overlap)
            return true;
        }
      return false;
    };
    membrane_colour.assign(n, 0);
    unsigned int n_colours = 1;
    for (unsigned int a = 0; a < n; ++a)
      {
        std::vector<bool> taken(n, false);
        for (unsigned int b = 0; b < a; ++b)
          if (touch(a, b))
            taken[membrane_colour[b]] = true;
        membrane_colour[a] =
          std::find(taken.begin(), taken.end(), false) - taken.begin();
        n_colours = std::max(n_colours, membrane_colour[a] + 1);
      }
    fe_collection = hp::FECollection<3>(FESystem<3>(FE_Q<3>(parameters.degree),
                                                    1 + n_colours),
                                        FE_Nothing<3>(1 + n_colours));
  }

  std::vector<unsigned int>
  CutCellDiffusion::ghost_penalty_fields(
    const DoFHandler<3>::active_cell_iterator &cell,
    const unsigned int                         face) const
  {
    if (cell->at_boundary(face) || cell->neighbor(face)->has_children())
      return {};
    const auto neighbor = cell->neighbor(face);
    if (!is_cut(*classifier, cell) && !is_cut(*classifier, neighbor))
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

  IndexSet
  CutCellDiffusion::unused_field_dofs() const
  {
    if (!reaction)
      return IndexSet(dof_handler.n_dofs());
    // Marked on the owned cells and summed on the owners, so that the ranks
    // agree on every DoF they share.
    LinearAlgebra::distributed::Vector<double> used(owned_dofs,
                                                    relevant_dofs,
                                                    communicator);
    const FiniteElement<3>                    &fe = fe_collection[lagrange];
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

  template <typename Function>
  void
  CutCellDiffusion::for_each_ghost_penalty_face(const Function &f) const
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

  CutCellDiffusion::MembraneCoupling
  CutCellDiffusion::membrane_coupling(
    const DoFHandler<3>::active_cell_iterator &cell) const
  {
    const unsigned int k      = parameters.degree;
    const double       h      = cell->minimum_vertex_distance();
    const double       gamma  = parameters.nitsche_penalty * k * (k + 1) / h;
    const double       plasma = permeability(cell->material_id());
    if (!reaction)
      return {plasma, 0., gamma * plasma};
    const double inside = reaction->permeability;
    const double mh     = std::sqrt(reaction->rate / inside) * h;
    const double stiff  = inside * std::sqrt(1. + mh * mh);
    const double w0 = stiff / (plasma + stiff), w1 = 1. - w0;
    return {w0 * plasma,
            w1 * inside,
            2. * gamma * (w0 * w0 * plasma + w1 * w1 * inside)};
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
    hold_unsupported_dofs();

    TimerOutput::Scope amg_scope(timer, "diffusion: AMG setup");
    TrilinosWrappers::PreconditionAMG::AdditionalData amg_data;
    amg_data.elliptic              = true;
    amg_data.higher_order_elements = parameters.degree > 1;
    amg_data.smoother_sweeps       = 2;
    amg_data.aggregation_threshold = 0.02;
    // The coarsest level (deal.II's set_parameters() asks ML for at most
    // 2000 rows) is factorised by KLU at every setup and solved at every
    // V-cycle; coarsening on to 500 rows is cheaper than both, and the
    // seven-cell solve's setup and solve together take a quarter less
    // (43 CG iterations instead of 42, doc/diffusion.md).
    Teuchos::ParameterList              ml_parameters;
    std::unique_ptr<Epetra_MultiVector> constant_modes;
    amg_data.set_parameters(ml_parameters, constant_modes, matrix);
    ml_parameters.set("coarse: max size", 500);
    amg.initialize(matrix, ml_parameters);
  }

  void
  CutCellDiffusion::hold_unsupported_dofs()
  {
    // A field can reach into a mesh cell as a sliver of round-off measure
    // (seen at a folded rim, tests/regression/folded_rim/run.prm), and if
    // no ghost penalty face reaches its DoFs either, their rows are
    // round-off of either sign, which the diagonal scaling in solve() would
    // divide by: hold them at zero, as the unused fields' DoFs are.
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

  void
  CutCellDiffusion::assemble_cells()
  {
    NonMatching::RegionUpdateFlags flags;
    flags.inside = update_gradients | update_JxW_values;
    if (reaction)
      flags.outside = update_values | update_gradients | update_JxW_values;
    flags.surface = update_values | update_gradients | update_JxW_values |
                    update_normal_vectors;
    const auto                fe_values_ptr = cut_cell_values(flags);
    NonMatching::FEValues<3> &fe_values     = *fe_values_ptr;
    const FiniteElement<3>   &fe            = fe_collection[lagrange];
    const unsigned int        n             = fe.n_dofs_per_cell();
    // The field of each shape function (0 the plasma's, 1 + c the inside
    // of the red cells of colour c), the sign it has in the jump
    // [P] = P₀ − P₁ across the membrane (P₁ = 0 for the membrane sink), and
    // on each mesh cell which shape functions are on its side (1), the
    // plasma's (0), or neither (-1: another colour's).
    std::vector<unsigned int> field(n);
    std::vector<int>          side(n);
    std::vector<double>       jump_sign(n), flux(n), jump(n);
    for (unsigned int i = 0; i < n; ++i)
      {
        field[i]     = fe.system_to_component_index(i).first;
        jump_sign[i] = field[i] == 0 ? 1. : -1.;
      }
    FullMatrix<double>                   cell_matrix(n, n);
    Vector<double>                       cell_rhs(n);
    std::vector<types::global_dof_index> dofs(n);
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned() && cell->active_fe_index() == lagrange)
        {
          fe_values.reinit(cell);
          cell_matrix                            = 0.;
          const std::vector<unsigned int> fields = fields_on(cell);
          for (unsigned int i = 0; i < n; ++i)
            side[i] = field[i] == 0 ? 0 : field[i] == fields.back() ? 1 : -1;
          // The plasma side: (αD ∇P₀, ∇q₀).
          if (const auto &inside = fe_values.get_inside_fe_values())
            {
              const double alpha_D = permeability(cell->material_id());
              for (const unsigned int q : inside->quadrature_point_indices())
                for (unsigned int i = 0; i < n; ++i)
                  if (side[i] == 0)
                    for (unsigned int j = 0; j < n; ++j)
                      if (side[j] == 0)
                        cell_matrix(i, j) +=
                          alpha_D * inside->shape_grad(i, q) *
                          inside->shape_grad(j, q) * inside->JxW(q);
            }
          // The cell side: (α_cD_c ∇P₁, ∇q₁) + (k P₁, q₁).
          if (reaction)
            if (const auto &outside = fe_values.get_outside_fe_values())
              for (const unsigned int q : outside->quadrature_point_indices())
                for (unsigned int i = 0; i < n; ++i)
                  if (side[i] == 1)
                    for (unsigned int j = 0; j < n; ++j)
                      if (side[j] == 1)
                        cell_matrix(i, j) +=
                          (reaction->permeability * outside->shape_grad(i, q) *
                             outside->shape_grad(j, q) +
                           reaction->rate * outside->shape_value(i, q) *
                             outside->shape_value(j, q)) *
                          outside->JxW(q);
          if (const auto &surface = fe_values.get_surface_fe_values())
            {
              // The symmetric Nitsche terms on the membrane: P = 0, or the
              // two sides glued.
              const MembraneCoupling coupling       = membrane_coupling(cell);
              const double           flux_weight[2] = {coupling.plasma_flux,
                                                       coupling.cell_flux};
              for (const unsigned int q : surface->quadrature_point_indices())
                {
                  // {αD ∂ₙφ_i} and [φ_i], once per shape function.
                  const Tensor<1, 3> &normal = surface->normal_vector(q);
                  for (unsigned int i = 0; i < n; ++i)
                    if (side[i] >= 0)
                      {
                        flux[i] = flux_weight[side[i]] *
                                  (normal * surface->shape_grad(i, q));
                        jump[i] = jump_sign[i] * surface->shape_value(i, q);
                      }
                    else
                      flux[i] = jump[i] = 0.;
                  const double JxW = surface->JxW(q);
                  for (unsigned int i = 0; i < n; ++i)
                    for (unsigned int j = 0; j < n; ++j)
                      cell_matrix(i, j) +=
                        (-flux[i] * jump[j] - flux[j] * jump[i] +
                         coupling.penalty * jump[i] * jump[j]) *
                        JxW;
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
      const double       h = cell->minimum_vertex_distance();
      const unsigned int n = interface_values.n_current_interface_dofs();
      local.reinit(n, n);
      for (const unsigned int f : ghost_penalty_fields(cell, face))
        {
          // γ_g αD h^(2j-1) ([∂ₙʲP], [∂ₙʲq]) for j = 1 .. k (k <= 2 here:
          // the third derivatives of Q3 are not penalised), for the field f.
          const auto   jumps  = interface_values[FEValuesExtractors::Scalar(f)];
          const double weight = parameters.ghost_penalty *
                                (f == 0 ? permeability(cell->material_id()) :
                                          reaction->permeability);
          for (const unsigned int q :
               interface_values.quadrature_point_indices())
            {
              // The jumps of ∂ₙφ_i and ∂ₙₙφ_i, once per shape function.
              const Tensor<1, 3> &normal = interface_values.normal(q);
              for (unsigned int i = 0; i < n; ++i)
                {
                  first[i] = normal * jumps.jump_in_gradients(i, q);
                  second[i] =
                    k > 1 ? normal * (jumps.jump_in_hessians(i, q) * normal) :
                            0.;
                }
              const double w1 = weight * h * interface_values.JxW(q);
              const double w2 = weight * h * h * h * interface_values.JxW(q);
              for (unsigned int i = 0; i < n; ++i)
                for (unsigned int j = 0; j < n; ++j)
                  local(i, j) +=
                    w1 * first[i] * first[j] + w2 * second[i] * second[j];
            }
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

    // j = −{αD ∂ₙP} + β [P] at each surface point, to its membrane (P₁ = 0
    // and {αD ∂ₙP} = αD ∂ₙP₀ for the membrane sink).
    std::vector<double>                  values, field_values;
    std::vector<Tensor<1, 3>>            gradients, field_gradients;
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
        // values: [P]; gradients: w₀ αD ∇P₀ + w₁ α_cD_c ∇P₁.
        const MembraneCoupling coupling       = membrane_coupling(cell);
        const double           flux_weight[2] = {coupling.plasma_flux,
                                                 coupling.cell_flux};
        values.assign(points.size(), 0.);
        gradients.assign(points.size(), Tensor<1, 3>());
        field_values.resize(points.size());
        field_gradients.resize(points.size());
        for (const unsigned int f : fields_on(cell))
          {
            const FEValuesExtractors::Scalar field(f);
            (*surface)[field].get_function_values(solution, field_values);
            (*surface)[field].get_function_gradients(solution, field_gradients);
            for (unsigned int q = 0; q < points.size(); ++q)
              {
                values[q] += (f == 0 ? 1. : -1.) * field_values[q];
                gradients[q] +=
                  flux_weight[f == 0 ? 0 : 1] * field_gradients[q];
              }
          }
        for (const unsigned int q : surface->quadrature_point_indices())
          {
            const double j = -(gradients[q] * surface->normal_vector(q)) +
                             coupling.penalty * values[q];
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
    return dof_handler.n_dofs() - n_unused_dofs;
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
               !fields_on(cell).empty();
      });
    data_out.set_flags(fast_vtk_flags());
    data_out.attach_dof_handler(dof_handler);
    // With a reaction, P inside the cells is a field of its own (one per
    // colour): zero outside them, as the plasma's is inside.
    const auto side = [this](const bool plasma) {
      return [this, plasma](const DoFHandler<3>::cell_iterator &cell) {
        const std::vector<unsigned int> fields = fields_on(cell);
        const bool there = plasma ? fields.front() == 0 : fields.back() > 0;
        return there ? (plasma ? 0u : fields.back()) :
                       numbers::invalid_unsigned_int;
      };
    };
    const SideField plasma_pressure("co_pressure", side(true)),
      cell_pressure("co_pressure_cell", side(false));
    if (reaction)
      {
        data_out.add_data_vector(solution, plasma_pressure);
        data_out.add_data_vector(solution, cell_pressure);
      }
    else
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
