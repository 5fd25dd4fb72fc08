#include <rbc_ifem/base/input_error.h>
#include <rbc_ifem/diffusion/cut_cell_geometry.h>
#include <rbc_ifem/geometry/capillary_mesh.h>

#include <deal.II/base/quadrature_lib.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/lac/affine_constraints.h>

#include <algorithm>
#include <limits>
#include <set>

namespace rbc_ifem
{
  namespace
  {
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
  } // namespace

  UnresolvedCutCells::UnresolvedCutCells(
    std::vector<CellId>                                         cells,
    const std::optional<std::pair<unsigned int, unsigned int>> &membranes)
    : std::runtime_error("cut cells that the level set cannot resolve")
    , cells(std::move(cells))
    , membranes(membranes)
  {}

  CutCellGeometry::CutCellGeometry(
    const parallel::TriangulationBase<3>   &mesh,
    const MembraneSurfaces                 &membranes,
    std::shared_ptr<const MembraneDistance> distance,
    const unsigned int                      degree,
    const std::optional<double>            &period,
    const Options                          &options,
    TimerOutput                            &timer)
    : triangulation(&mesh)
    , surfaces(membranes)
    , distance(std::move(distance))
    , k(degree)
    , segment_period(period)
    , communicator(mesh.get_communicator())
    , timer(timer)
    , cached_mapping(degree)
    , cell_quadrature(QGauss<3>(degree + 1))
    , line_quadrature(QGauss<1>(degree + 1))
    , level_set_fe(degree)
  {
    TimerOutput::Scope scope(timer, "diffusion: setup");
    cache_mapping();
    compute_level_set();
    // Both kinds of unresolved cells at once, so that one refinement takes
    // care of them; one membrane shares no cell, and the surface points of a
    // mesh that will be refined are not needed.
    const std::vector<CellId> ridges =
      options.refine_ridges ? ridge_cells() : std::vector<CellId>();
    if (surfaces.size() == 1 &&
        Utilities::MPI::logical_or(!ridges.empty(), communicator))
      throw_if_unresolved(ridges, SharedCells());
    SharedCells shared = locate_surface_points();
    if (options.separate_insides)
      add_gap_cells(shared);
    throw_if_unresolved(ridges, shared);
    if (options.separate_insides)
      {
        find_insides();
        colour_membranes();
      }
  }

  CutCellGeometry::~CutCellGeometry()
  {
    // The classifier refers to the level set's DoFHandler: release it first.
    classifier.reset();
    level_set_dofs.clear();
  }

  const parallel::TriangulationBase<3> &
  CutCellGeometry::mesh() const
  {
    return *triangulation;
  }

  const MembraneSurfaces &
  CutCellGeometry::membranes() const
  {
    return surfaces;
  }

  unsigned int
  CutCellGeometry::degree() const
  {
    return k;
  }

  const std::optional<double> &
  CutCellGeometry::period() const
  {
    return segment_period;
  }

  const MappingQCache<3> &
  CutCellGeometry::mapping() const
  {
    return cached_mapping;
  }

  const DoFHandler<3> &
  CutCellGeometry::level_set_dof_handler() const
  {
    return level_set_dofs;
  }

  const LinearAlgebra::distributed::Vector<double> &
  CutCellGeometry::level_set() const
  {
    return level_set_values;
  }

  NonMatching::LocationToLevelSet
  CutCellGeometry::location(const Triangulation<3>::cell_iterator &cell) const
  {
    return classifier->location_to_level_set(cell);
  }

  bool
  CutCellGeometry::is_cut(const Triangulation<3>::cell_iterator &cell) const
  {
    return location(cell) == NonMatching::LocationToLevelSet::intersected;
  }

  const std::map<unsigned int, CutCellGeometry::SurfacePoints> &
  CutCellGeometry::surface_points() const
  {
    return points;
  }

  unsigned int
  CutCellGeometry::inside_of(const Triangulation<3>::cell_iterator &cell) const
  {
    return cell_membrane.at(cell->active_cell_index());
  }

  unsigned int
  CutCellGeometry::colour(const unsigned int m) const
  {
    return membrane_colour.at(m);
  }

  unsigned int
  CutCellGeometry::n_colours() const
  {
    return colours;
  }

  std::unique_ptr<NonMatching::FEValues<3>>
  CutCellGeometry::cut_cell_values(
    const hp::FECollection<3>            &fe_collection,
    const NonMatching::RegionUpdateFlags &flags) const
  {
    return std::make_unique<NonMatching::FEValues<3>>(mapping_collection,
                                                      fe_collection,
                                                      cell_quadrature,
                                                      line_quadrature,
                                                      flags,
                                                      *classifier,
                                                      level_set_dofs,
                                                      level_set_values);
  }

  void
  CutCellGeometry::cache_mapping()
  {
    const SupportPointsOfMappingQ exact(k);
    const unsigned int            n_points = Utilities::pow(k + 1, 3);
    cached_mapping.initialize(
      *triangulation, [&](const Triangulation<3>::cell_iterator &cell) {
        // Nothing here evaluates on a parent or an artificial cell: they
        // keep a placeholder, and cost nothing.
        if (cell->is_active() && !cell->is_artificial())
          return exact.compute_mapping_support_points(cell);
        return std::vector<Point<3>>(n_points, cell->vertex(0));
      });
    // The collection holds a copy, which shares the cache just made.
    mapping_collection = hp::MappingCollection<3>(cached_mapping);
  }

  void
  CutCellGeometry::compute_level_set()
  {
    TimerOutput::Scope scope(timer, "diffusion: level set");
    level_set_dofs.reinit(*triangulation);
    level_set_dofs.distribute_dofs(level_set_fe);
    const IndexSet owned = level_set_dofs.locally_owned_dofs();
    IndexSet       relevant;
    DoFTools::extract_locally_relevant_dofs(level_set_dofs, relevant);

    // Every node of an owned cell is computed here, those other ranks own
    // too: the ridge check needs their closest points. A node outside the
    // lumen (vessel wall, gas layer) is in the plasma's side of every
    // membrane, since no membrane leaves the lumen (locate_surface_points()
    // checks, on the nodes of the lumen), and only its distance matters:
    // the nearest membrane sample's, a tenth of the time, is within the
    // sample spacing of it. Those nodes are over half of them.
    LinearAlgebra::distributed::Vector<double> owned_values(owned,
                                                            communicator);
    closest_points.clear();
    for (const LevelSetNode &node : level_set_nodes())
      {
        double signed_distance;
        if (node.in_lumen)
          {
            const MembraneDistance::ClosestPoint closest =
              distance->closest_point(node.position);
            signed_distance = closest.signed_distance;
            closest_points.emplace(node.dof, closest);
          }
        else
          signed_distance = distance->nearest_sample_distance(node.position);
        if (owned.is_element(node.dof))
          owned_values[node.dof] = -signed_distance;
      }
    // Hanging values take the coarse side's, so that neighbours agree on
    // where the membrane is.
    AffineConstraints<double> hanging(relevant);
    DoFTools::make_hanging_node_constraints(level_set_dofs, hanging);
    hanging.close();
    hanging.distribute(owned_values);
    level_set_values.reinit(owned, relevant, communicator);
    for (const auto dof : owned)
      level_set_values[dof] = owned_values[dof];
    level_set_values.update_ghost_values();

    classifier =
      std::make_unique<NonMatching::MeshClassifier<3>>(level_set_dofs,
                                                       level_set_values);
    classifier->reclassify();
  }

  std::vector<CutCellGeometry::LevelSetNode>
  CutCellGeometry::level_set_nodes() const
  {
    // Every cell that holds a node of an owned cell shares a vertex with
    // it, so it is owned or a ghost here.
    std::map<types::global_dof_index, std::pair<CellId, Point<3>>> placed;
    std::set<types::global_dof_index>    wanted, in_lumen;
    FEValues<3>                          fe_values(cached_mapping,
                          level_set_fe,
                          Quadrature<3>(level_set_fe.get_unit_support_points()),
                          update_quadrature_points);
    std::vector<types::global_dof_index> dofs(level_set_fe.n_dofs_per_cell());
    for (const auto &cell : level_set_dofs.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          cell->get_dof_indices(dofs);
          wanted.insert(dofs.begin(), dofs.end());
        }
    for (const auto &cell : level_set_dofs.active_cell_iterators())
      if (!cell->is_artificial())
        {
          cell->get_dof_indices(dofs);
          if (cell->material_id() == Material::plasma)
            in_lumen.insert(dofs.begin(), dofs.end());
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
    std::vector<LevelSetNode> nodes;
    nodes.reserve(placed.size());
    for (const auto &[dof, placement] : placed)
      nodes.push_back({dof, placement.second, in_lumen.count(dof) > 0});
    return nodes;
  }

  bool
  CutCellGeometry::is_cut_in_lumen(
    const Triangulation<3>::cell_iterator &cell) const
  {
    // Only the lumen's nodes have closest points; a cut cell outside it
    // is an input error, which locate_surface_points() reports.
    return cell->material_id() == Material::plasma && is_cut(cell);
  }

  std::vector<CellId>
  CutCellGeometry::ridge_cells() const
  {
    std::vector<CellId>                  cells;
    std::vector<types::global_dof_index> dofs(level_set_fe.n_dofs_per_cell());
    for (const auto &cell : level_set_dofs.active_cell_iterators())
      if (cell->is_locally_owned() && is_cut_in_lumen(cell))
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
  CutCellGeometry::add_gap_cells(SharedCells &shared) const
  {
    std::vector<types::global_dof_index> dofs(level_set_fe.n_dofs_per_cell());
    for (const auto &cell : level_set_dofs.active_cell_iterators())
      if (cell->is_locally_owned() && is_cut_in_lumen(cell))
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
  CutCellGeometry::throw_if_unresolved(const std::vector<CellId> &ridges,
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

  CutCellGeometry::SharedCells
  CutCellGeometry::locate_surface_points()
  {
    TimerOutput::Scope             scope(timer, "diffusion: surface points");
    NonMatching::RegionUpdateFlags flags;
    flags.surface = update_quadrature_points;
    // NonMatching::FEValues keeps a pointer to the collection.
    const hp::FECollection<3> fe_collection(level_set_fe);
    const auto fe_values_ptr            = cut_cell_values(fe_collection, flags);
    NonMatching::FEValues<3> &fe_values = *fe_values_ptr;
    // What the membranes ask of the mesh, found on this rank's cut cells:
    // [0] a cut cell outside the plasma (a membrane in the vessel wall) and
    // [1 + m] the number of surface points on membrane m; and the cut cells
    // that two membranes share.
    std::vector<unsigned int> findings(1 + surfaces.size(), 0);
    SharedCells               shared;
    points.clear();
    for (const auto &cell : level_set_dofs.active_cell_iterators())
      if (cell->is_locally_owned() && is_cut(cell))
        {
          fe_values.reinit(cell);
          const auto &surface = fe_values.get_surface_fe_values();
          if (!surface)
            continue;
          if (cell->material_id() != Material::plasma)
            findings[0] = 1;
          SurfacePoints &here = points[cell->active_cell_index()];
          for (const auto &x : surface->get_quadrature_points())
            {
              here.push_back(distance->closest_point(x));
              ++findings[1 + here.back().membrane];
            }
          for (const auto &point : here)
            if (point.membrane != here.front().membrane)
              {
                shared.cells.push_back(cell->id());
                shared.membranes = {
                  std::min(point.membrane, here.front().membrane),
                  std::max(point.membrane, here.front().membrane)};
                break;
              }
        }
    Utilities::MPI::max(findings, communicator, findings);
    if (findings[0] > 0)
      throw InputError("Layout",
                       "a membrane in the vessel wall",
                       "a membrane reaches out of the lumen into the vessel "
                       "wall; every cell must lie inside the capillary.");
    for (unsigned int m = 0; m < surfaces.size(); ++m)
      if (findings[1 + m] == 0)
        throw InputError("Layout",
                         "cell " + std::to_string(m),
                         "this membrane cuts no cell of the diffusion mesh: "
                         "it lies outside the capillary, or within one "
                         "cell of the mesh.");
    return shared;
  }

  void
  CutCellGeometry::find_insides()
  {
    // The level set node deepest inside a red cell is closer to its
    // membrane than to any other: the straight line to another crosses it.
    cell_membrane.assign(triangulation->n_active_cells(),
                         numbers::invalid_unsigned_int);
    FEValues<3>                          nodes(cached_mapping,
                      level_set_fe,
                      Quadrature<3>(level_set_fe.get_unit_support_points()),
                      update_quadrature_points);
    std::vector<types::global_dof_index> dofs(level_set_fe.n_dofs_per_cell());
    for (const auto &cell : level_set_dofs.active_cell_iterators())
      if (!cell->is_artificial() &&
          location(cell) != NonMatching::LocationToLevelSet::inside)
        {
          cell->get_dof_indices(dofs);
          const auto deepest =
            std::max_element(dofs.begin(), dofs.end(), [&](auto a, auto b) {
              return level_set_values[a] < level_set_values[b];
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
  CutCellGeometry::colour_membranes()
  {
    // Each membrane's box around the mesh cells that reach into it.
    const unsigned int  n = surfaces.size();
    std::vector<double> lower(3 * n, std::numeric_limits<double>::max()),
      upper(3 * n, std::numeric_limits<double>::lowest());
    for (const auto &cell : triangulation->active_cell_iterators())
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
      for (const double shift :
           segment_period ?
             std::vector<double>{0., *segment_period, -*segment_period} :
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
    colours = 1;
    for (unsigned int a = 0; a < n; ++a)
      {
        std::vector<bool> taken(n, false);
        for (unsigned int b = 0; b < a; ++b)
          if (touch(a, b))
            taken[membrane_colour[b]] = true;
        membrane_colour[a] =
          std::find(taken.begin(), taken.end(), false) - taken.begin();
        colours = std::max(colours, membrane_colour[a] + 1);
      }
  }
} // namespace rbc_ifem
