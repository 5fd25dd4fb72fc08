#include <rbc_ifem/base/output.h>
#include <rbc_ifem/base/ranks.h>
#include <rbc_ifem/coupling/cell_population.h>
#include <rbc_ifem/coupling/membrane_forces.h>
#include <rbc_ifem/geometry/capillary_mesh.h>
#include <rbc_ifem/geometry/cell_surface.h>
#include <rbc_ifem/membrane/deformed_surface_mapping.h>

#include <deal.II/numerics/data_out.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <set>

namespace rbc_ifem
{
  namespace
  {
    /// The longest edge of the cells of @p surface [µm].
    double
    longest_edge(const Triangulation<2, 3> &surface)
    {
      double longest = 0.;
      for (const auto &cell : surface.active_cell_iterators())
        for (const unsigned int l : cell->line_indices())
          longest = std::max(longest, cell->line(l)->diameter());
      return longest;
    }
  } // namespace

  CellPopulation::CellPopulation(const std::vector<CellPlacement> &placements,
                                 const CellParameters             &cells,
                                 const MembraneParameters         &membrane,
                                 const MPI_Comm                    communicator,
                                 const std::optional<double>      &period)
    : placements(placements)
    , shape_of_cells(EvansFungShape::of(cells))
    , surface_refinements(cells.surface_refinements)
    , membrane_parameters(membrane)
    , flat_mapping(1)
    , reference_meshes(placements.size())
    , period(period)
  {
    // With at least as many cells as ranks each cell has one owner, which
    // computes it alone; with fewer, one owner per cell would leave ranks
    // idle (a single cell on 2 ranks: its stiffness took twice as long),
    // so every rank keeps and computes every cell, each membrane's cell
    // loops split over all ranks.
    const bool fewer_cells_than_ranks =
      placements.size() < Utilities::MPI::n_mpi_processes(communicator);
    if (!fewer_cells_than_ranks)
      cell_owners = CellOwners(communicator);
    // Every cell is the one reference shape placed elsewhere: they share
    // the first cell's numbering and stiffness pattern. Each is made here
    // for its reference positions and measures; with the cells shared out
    // it is dropped again (its owner makes it anew, place_owners()), so
    // that no rank holds every cell's at once. The first stays as the model.
    for (unsigned int c = 0; c < placements.size(); ++c)
      {
        std::unique_ptr<Triangulation<2, 3>> mesh;
        const std::shared_ptr<Membrane>      made = make_membrane(c, mesh);
        if (c == 0)
          model = made;
        if (c == 0 || !cell_owners.shared())
          reference_meshes[c] = std::move(mesh);
        cell_membranes.push_back(holds(c) ? made : model);
        x.push_back(made->reference_positions());
        forces.emplace_back(x.back().size());
        n_membrane_points += made->nodes().size();
        areas0.push_back(made->reference_area());
        volumes0.push_back(made->reference_volume());
        largest_spacing =
          std::max(largest_spacing,
                   longest_edge(made->get_dof_handler().get_triangulation()) /
                     made->get_dof_handler().get_fe().degree);
      }
    place_owners();
    if (fewer_cells_than_ranks)
      for (const std::shared_ptr<Membrane> &membrane : cell_membranes)
        membrane->share_work(communicator);
    add_force(
      std::make_unique<MembraneElasticity>(cell_membranes, cell_owners));
  }

  std::shared_ptr<Membrane>
  CellPopulation::make_membrane(
    const unsigned int                    c,
    std::unique_ptr<Triangulation<2, 3>> &mesh) const
  {
    mesh = std::make_unique<Triangulation<2, 3>>();
    create_cell_surface(*mesh,
                        shape_of_cells,
                        placements[c],
                        surface_refinements);
    return std::make_shared<Membrane>(*mesh, membrane_parameters, model.get());
  }

  bool
  CellPopulation::holds(const unsigned int c) const
  {
    return reference_meshes[c] != nullptr;
  }

  const CellOwners &
  CellPopulation::owners() const
  {
    return cell_owners;
  }

  unsigned int
  CellPopulation::writer(const unsigned int c,
                         const MPI_Comm     communicator) const
  {
    return cell_owners.shared() ? cell_owners.owner(c) :
                                  CellOwners(communicator).owner(c);
  }

  std::vector<unsigned int>
  CellPopulation::writers(const MPI_Comm communicator) const
  {
    std::set<unsigned int> ranks;
    for (unsigned int c = 0; c < size(); ++c)
      ranks.insert(writer(c, communicator));
    return {ranks.begin(), ranks.end()};
  }

  void
  CellPopulation::place_owners()
  {
    if (cell_owners.shared())
      {
        std::vector<double>       where(size());
        std::vector<unsigned int> points(size()), before(size());
        for (unsigned int c = 0; c < size(); ++c)
          {
            const auto &nodes = model->nodes();
            for (const auto &dofs : nodes)
              where[c] += x[c][dofs[0]] / nodes.size();
            where[c] = wrap_into_segment(Point<3>(where[c], 0., 0.), period)[0];
            points[c] = nodes.size();
            before[c] = cell_owners.owner(c);
          }
        const std::vector<unsigned int> lost = cell_owners.place(where, points);
        // The last forces go with their cells: the new owner writes them.
        cell_owners.hand_over(before, forces);
        ++n_stiffness_changes;
        if (!lost.empty())
          stiffnesses.clear();
        // The model stays with every rank, without the data of an owner.
        if (std::find(lost.begin(), lost.end(), 0u) != lost.end())
          model->forget_owner_data();
      }
    keep_own_membranes();
  }

  void
  CellPopulation::keep_own_membranes()
  {
    for (unsigned int c = 1; c < size(); ++c)
      if (cell_owners.owns(c) && !holds(c))
        cell_membranes[c] = make_membrane(c, reference_meshes[c]);
      else if (!cell_owners.owns(c) && holds(c))
        {
          cell_membranes[c] = model;
          reference_meshes[c].reset();
        }
  }

  unsigned int
  CellPopulation::size() const
  {
    return cell_membranes.size();
  }

  unsigned int
  CellPopulation::n_points() const
  {
    return n_membrane_points;
  }

  std::vector<Point<3>>
  CellPopulation::points() const
  {
    std::vector<Point<3>> result;
    result.reserve(n_membrane_points);
    for (unsigned int c = 0; c < size(); ++c)
      for (const auto &dofs : cell_membranes[c]->nodes())
        result.emplace_back(x[c][dofs[0]], x[c][dofs[1]], x[c][dofs[2]]);
    return result;
  }

  void
  CellPopulation::add_force(std::unique_ptr<CellForce> force)
  {
    cell_forces.push_back(std::move(force));
  }

  std::vector<Tensor<1, 3>>
  CellPopulation::compute_forces()
  {
    add_every_cell_force();
    // Each rank added its own cells' forces: one reduction for them all.
    std::vector<double> totals = owned_totals();
    cell_owners.add_up(forces, make_array_view(totals));
    take_totals(totals);
    return per_point(forces);
  }

  std::vector<Tensor<1, 3>>
  CellPopulation::compute_owned_forces()
  {
    add_every_cell_force();
    std::vector<double>         totals = owned_totals();
    std::vector<Vector<double>> no_forces;
    cell_owners.add_up(no_forces, make_array_view(totals));
    take_totals(totals);
    return per_point(forces);
  }

  const std::vector<Vector<double>> &
  CellPopulation::last_forces() const
  {
    return forces;
  }

  bool
  CellPopulation::forces_finite() const
  {
    return all_forces_finite;
  }

  void
  CellPopulation::add_every_cell_force()
  {
    for (Vector<double> &f : forces)
      f = 0.;
    external_force = 0.;
    total_energy   = 0.;
    for (const auto &force : cell_forces)
      {
        const CellForceReport report = force->add_forces(x, forces);
        external_force += report.external_force;
        total_energy += report.energy;
      }
  }

  std::vector<double>
  CellPopulation::owned_totals() const
  {
    double n_not_finite = 0.;
    for (unsigned int c = 0; c < size(); ++c)
      if (cell_owners.owns(c))
        for (const double f : forces[c])
          n_not_finite += std::isfinite(f) ? 0. : 1.;
    return {total_energy,
            external_force[0],
            external_force[1],
            external_force[2],
            n_not_finite};
  }

  void
  CellPopulation::take_totals(const std::vector<double> &totals)
  {
    total_energy = totals[0];
    for (unsigned int d = 0; d < 3; ++d)
      external_force[d] = totals[d + 1];
    all_forces_finite = totals[4] == 0.;
  }

  void
  CellPopulation::linearize()
  {
    stiffnesses.clear();
    for (const auto &force : cell_forces)
      if (auto K = force->stiffness(x))
        stiffnesses.push_back(std::move(K));
    ++n_stiffness_changes;
  }

  std::vector<Vector<double>>
  CellPopulation::per_cell(const std::vector<Tensor<1, 3>> &values) const
  {
    AssertDimension(values.size(), n_membrane_points);
    std::vector<Vector<double>> result;
    auto                        point = values.begin();
    for (unsigned int c = 0; c < size(); ++c)
      {
        result.emplace_back(x[c].size());
        for (const auto &dofs : cell_membranes[c]->nodes())
          {
            for (unsigned int d = 0; d < 3; ++d)
              result[c][dofs[d]] = (*point)[d];
            ++point;
          }
      }
    return result;
  }

  std::vector<Tensor<1, 3>>
  CellPopulation::per_point(const std::vector<Vector<double>> &values) const
  {
    std::vector<Tensor<1, 3>> result;
    result.reserve(n_membrane_points);
    for (unsigned int c = 0; c < size(); ++c)
      for (const auto &dofs : cell_membranes[c]->nodes())
        result.push_back(Tensor<1, 3>(
          {values[c][dofs[0]], values[c][dofs[1]], values[c][dofs[2]]}));
    return result;
  }

  std::vector<Vector<double>>
  CellPopulation::owned_rows_product(
    const std::vector<Tensor<1, 3>> &displacements) const
  {
    const std::vector<Vector<double>> v = per_cell(displacements);
    std::vector<Vector<double>>       Kv(v.size());
    for (unsigned int c = 0; c < size(); ++c)
      Kv[c].reinit(v[c].size());
    for (const auto &K : stiffnesses)
      K->add_product(v, Kv);
    return Kv;
  }

  std::vector<Vector<double>>
  CellPopulation::owned_rows_diagonal() const
  {
    std::vector<Vector<double>> diagonal(size());
    for (unsigned int c = 0; c < size(); ++c)
      diagonal[c].reinit(x[c].size());
    for (const auto &K : stiffnesses)
      K->add_diagonal(diagonal);
    return diagonal;
  }

  std::vector<Tensor<1, 3>>
  CellPopulation::stiffness_product(
    const std::vector<Tensor<1, 3>> &displacements) const
  {
    std::vector<Vector<double>> Kv = owned_rows_product(displacements);
    cell_owners.add_up(Kv, {});
    return per_point(Kv);
  }

  std::vector<Tensor<1, 3>>
  CellPopulation::stiffness_diagonal() const
  {
    std::vector<Vector<double>> diagonal = owned_rows_diagonal();
    cell_owners.add_up(diagonal, {});
    return per_point(diagonal);
  }

  std::vector<Tensor<1, 3>>
  CellPopulation::owned_stiffness_product(
    const std::vector<Tensor<1, 3>> &displacements) const
  {
    return per_point(owned_rows_product(displacements));
  }

  std::vector<Tensor<1, 3>>
  CellPopulation::owned_stiffness_diagonal() const
  {
    return per_point(owned_rows_diagonal());
  }

  std::vector<unsigned int>
  CellPopulation::points_read() const
  {
    std::vector<bool> read(size());
    for (unsigned int c = 0; c < size(); ++c)
      read[c] = cell_owners.owns(c);
    for (const auto &K : stiffnesses)
      K->mark_cells_read(read);
    std::vector<unsigned int> points;
    unsigned int              first = 0;
    for (unsigned int c = 0; c < size(); ++c)
      {
        const unsigned int n = cell_membranes[c]->nodes().size();
        for (unsigned int i = first; read[c] && i < first + n; ++i)
          points.push_back(i);
        first += n;
      }
    return points;
  }

  std::vector<unsigned int>
  CellPopulation::point_owners(
    const std::vector<unsigned int> &fluid_ranks) const
  {
    if (!cell_owners.shared())
      return fluid_ranks;
    std::vector<unsigned int> owners;
    owners.reserve(n_membrane_points);
    for (unsigned int c = 0; c < size(); ++c)
      owners.insert(owners.end(),
                    cell_membranes[c]->nodes().size(),
                    cell_owners.owner(c));
    return owners;
  }

  unsigned int
  CellPopulation::stiffness_serial() const
  {
    return n_stiffness_changes;
  }

  Tensor<1, 3>
  CellPopulation::held_force() const
  {
    return external_force;
  }

  double
  CellPopulation::energy() const
  {
    return total_energy;
  }

  const std::vector<std::shared_ptr<Membrane>> &
  CellPopulation::membranes() const
  {
    return cell_membranes;
  }

  void
  CellPopulation::move(const std::vector<Tensor<1, 3>> &velocities,
                       const double                     time_step)
  {
    AssertDimension(velocities.size(), n_membrane_points);
    auto velocity = velocities.begin();
    for (unsigned int c = 0; c < size(); ++c)
      for (const auto &dofs : cell_membranes[c]->nodes())
        {
          for (unsigned int d = 0; d < 3; ++d)
            x[c][dofs[d]] += time_step * (*velocity)[d];
          ++velocity;
        }
    place_owners();
  }

  namespace
  {
    /// How many numbers a CellShape holds.
    constexpr unsigned int n_shape_numbers = 11;

    /// A CellShape's numbers in one Vector, and back: what the owners add
    /// up.
    Vector<double>
    packed(const CellShape &s)
    {
      const std::array<double, n_shape_numbers> numbers{
        {s.centroid[0],
         s.centroid[1],
         s.centroid[2],
         s.area,
         s.volume,
         s.axial_length,
         s.max_radius,
         s.deformation_index,
         s.taylor_deformation,
         s.inclination,
         s.largest_local_area_change}};
      return Vector<double>(numbers.begin(), numbers.end());
    }

    CellShape
    unpacked(const Vector<double> &v)
    {
      CellShape s;
      s.centroid                  = Point<3>(v[0], v[1], v[2]);
      s.area                      = v[3];
      s.volume                    = v[4];
      s.axial_length              = v[5];
      s.max_radius                = v[6];
      s.deformation_index         = v[7];
      s.taylor_deformation        = v[8];
      s.inclination               = v[9];
      s.largest_local_area_change = v[10];
      return s;
    }
  } // namespace

  std::vector<CellShape>
  CellPopulation::shapes() const
  {
    // Each owner measures its cells, one surface at a time; one sum gives
    // every rank all of them (the others' entries are zeros).
    std::vector<Vector<double>> measured(size(),
                                         Vector<double>(n_shape_numbers));
    Triangulation<2, 3>         surface;
    for (unsigned int c = 0; c < size(); ++c)
      if (cell_owners.owns(c))
        {
          surface.clear();
          cell_membranes[c]->build_surface(x[c], surface);
          measured[c] = packed(shape(c, surface));
        }
    cell_owners.add_up(measured, {});
    std::vector<CellShape> result;
    for (const Vector<double> &v : measured)
      result.push_back(unpacked(v));
    return result;
  }

  std::vector<double>
  CellPopulation::volumes() const
  {
    std::vector<Vector<double>> measured(size(), Vector<double>(1));
    for (unsigned int c = 0; c < size(); ++c)
      if (cell_owners.owns(c))
        measured[c][0] = cell_membranes[c]->volume(x[c]);
    cell_owners.add_up(measured, {});
    std::vector<double> result;
    for (const Vector<double> &v : measured)
      result.push_back(v[0]);
    return result;
  }

  CellShape
  CellPopulation::shape(const unsigned int         c,
                        const Triangulation<2, 3> &surface) const
  {
    CellShape             shape;
    const SurfaceMeasures measures = measure_surface(surface, flat_mapping);
    shape.centroid                 = measures.centroid;
    shape.area                     = cell_membranes[c]->area(x[c]);
    shape.volume                   = cell_membranes[c]->volume(x[c]);
    double x_min = std::numeric_limits<double>::max(), x_max = -x_min;
    for (const auto &dofs : cell_membranes[c]->nodes())
      {
        const Point<3> p(x[c][dofs[0]], x[c][dofs[1]], x[c][dofs[2]]);
        x_min            = std::min(x_min, p[0]);
        x_max            = std::max(x_max, p[0]);
        shape.max_radius = std::max(shape.max_radius,
                                    std::hypot(p[1] - shape.centroid[1],
                                               p[2] - shape.centroid[2]));
      }
    shape.axial_length      = x_max - x_min;
    shape.deformation_index = (shape.axial_length - 2. * shape.max_radius) /
                              (shape.axial_length + 2. * shape.max_radius);
    const ShearPlaneEllipse ellipse =
      shear_plane_ellipse(measures.second_moment);
    shape.taylor_deformation = ellipse.taylor_deformation;
    shape.inclination        = ellipse.inclination;
    shape.largest_local_area_change =
      cell_membranes[c]->local_area_changes(x[c]).linfty_norm();
    return shape;
  }

  std::vector<std::unique_ptr<Triangulation<2, 3>>>
  CellPopulation::current_surfaces() const
  {
    std::vector<std::unique_ptr<Triangulation<2, 3>>> surfaces;
    for (unsigned int c = 0; c < size(); ++c)
      {
        surfaces.push_back(std::make_unique<Triangulation<2, 3>>());
        cell_membranes[c]->build_surface(x[c], *surfaces.back());
      }
    return surfaces;
  }

  namespace
  {
    /// The current surfaces and the mapping that curves them, which a
    /// MembraneSurfaces view keeps alive.
    struct CurrentSurfaces
    {
      CurrentSurfaces(
        std::vector<std::unique_ptr<Triangulation<2, 3>>> owned,
        const std::function<std::shared_ptr<const Membrane>(unsigned int)>
                                          &membrane_of,
        const std::vector<Vector<double>> &positions)
        : owned(std::move(owned))
        , mapping(meshes(), membrane_of, positions)
      {}

      std::vector<const Triangulation<2, 3> *>
      meshes() const
      {
        std::vector<const Triangulation<2, 3> *> pointers;
        for (const auto &surface : owned)
          pointers.push_back(surface.get());
        return pointers;
      }

      const std::vector<std::unique_ptr<Triangulation<2, 3>>> owned;
      const DeformedSurfaceMapping                            mapping;
    };

    /// A Membrane made for a while, with the reference mesh it lives on
    /// (declared first, so destroyed last).
    struct MadeMembrane
    {
      std::unique_ptr<Triangulation<2, 3>> mesh;
      std::shared_ptr<Membrane>            membrane;
    };
  } // namespace

  MembraneSurfaces
  CellPopulation::membrane_surfaces() const
  {
    // The mapping curves each surface by its cell's reference shape: it
    // needs each cell's own Membrane while it takes that surface's support
    // points, and this rank makes those it does not keep one at a time.
    const auto membrane_of =
      [this](const unsigned int c) -> std::shared_ptr<const Membrane> {
      if (holds(c))
        return cell_membranes[c];
      const auto made = std::make_shared<MadeMembrane>();
      made->membrane  = make_membrane(c, made->mesh);
      return std::shared_ptr<const Membrane>(made, made->membrane.get());
    };
    const auto current =
      std::make_shared<const CurrentSurfaces>(current_surfaces(),
                                              membrane_of,
                                              x);
    return MembraneSurfaces(current->meshes(), current->mapping, current);
  }

  double
  CellPopulation::point_spacing() const
  {
    return largest_spacing;
  }

  double
  CellPopulation::reference_area(const unsigned int c) const
  {
    return areas0[c];
  }

  double
  CellPopulation::reference_volume(const unsigned int c) const
  {
    return volumes0[c];
  }

  std::vector<std::string>
  CellPopulation::write_vtu(const std::string &directory,
                            const std::string &name,
                            const unsigned int counter,
                            const FieldData   &field_data,
                            const MPI_Comm     communicator) const
  {
    const unsigned int       rank = this_rank(communicator);
    std::vector<std::string> files;
    for (unsigned int c = 0; c < size(); ++c)
      {
        files.push_back(name + "_" + std::to_string(c) + "_" +
                        Utilities::int_to_string(counter, 4) + ".vtu");
        if (writer(c, communicator) != rank)
          continue;
        DataOut<2, 3> data_out;
        build_patches(c, data_out);
        data_out.set_flags(fast_vtk_flags());
        rbc_ifem::write_vtu(data_out,
                            directory + "/" + files.back(),
                            field_data);
      }
    return files;
  }

  std::string
  CellPopulation::write_grouped_vtu(const std::string &directory,
                                    const std::string &name,
                                    const unsigned int counter,
                                    const FieldData   &field_data,
                                    const MPI_Comm     communicator) const
  {
    const std::vector<unsigned int> ranks = writers(communicator);
    const unsigned int              rank  = this_rank(communicator);
    // The first of this rank's cells takes the patches of the others.
    std::optional<DataOut<2, 3>> own;
    for (unsigned int c = 0; c < size(); ++c)
      if (writer(c, communicator) == rank)
        {
          if (!own)
            build_patches(c, own.emplace());
          else
            {
              DataOut<2, 3> next;
              build_patches(c, next);
              own->merge_patches(next);
            }
        }
    const std::string file =
      name + "_" + Utilities::int_to_string(counter, 4) + ".pvtu";
    if (!own)
      return file;
    own->set_flags(fast_vtk_flags());
    return write_vtu_pieces(
      *own, directory, name, counter, ranks, communicator, field_data);
  }

  void
  CellPopulation::build_patches(const unsigned int c,
                                DataOut<2, 3>     &data_out) const
  {
    const Vector<double> density =
      cell_membranes[c]->force_densities(x[c], forces[c]);
    cell_membranes[c]->build_patches(data_out,
                                     x[c],
                                     {{"force", forces[c]},
                                      {"force_density", density}},
                                     {{"cell", c}});
  }

  const std::vector<Vector<double>> &
  CellPopulation::positions() const
  {
    return x;
  }

  void
  CellPopulation::set_positions(const std::vector<Vector<double>> &positions)
  {
    AssertDimension(positions.size(), x.size());
    x = positions;
    place_owners();
  }
} // namespace rbc_ifem
