#include <rbc_ifem/geometry/capillary_mesh.h>

#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/grid/manifold_lib.h>
#include <deal.II/grid/tria_description.h>
#include <deal.II/numerics/rtree.h>

#include <cmath>

namespace rbc_ifem
{
  namespace
  {
    constexpr types::manifold_id cylindrical_manifold_id = 0;
    constexpr types::manifold_id transfinite_manifold_id = 1;

    double
    distance_from_axis(const Point<3> &p)
    {
      return std::hypot(p[1], p[2]);
    }

    /**
     * The coarse cross-section: a central square, a ring of 4 cells from
     * the square out to the circle radii[0], and one ring of 4 cells out to
     * each further radius. Ring k (k >= 1) gets ring_materials[k].
     */
    void
    create_cross_section(Triangulation<2>                      &section,
                         const std::vector<double>             &radii,
                         const std::vector<types::material_id> &ring_materials)
    {
      // Vertex 4j + k sits at angle 45° + 90° k on circle j; circle 0 holds
      // the corners of the central square, of half-width 0.4 radii[0].
      std::vector<double> circle_radii{0.4 * std::sqrt(2.) * radii[0]};
      circle_radii.insert(circle_radii.end(), radii.begin(), radii.end());
      std::vector<Point<2>> vertices;
      for (const double r : circle_radii)
        for (unsigned int k = 0; k < 4; ++k)
          vertices.emplace_back(r * std::cos(numbers::PI / 4. * (2 * k + 1)),
                                r * std::sin(numbers::PI / 4. * (2 * k + 1)));

      std::vector<CellData<2>> cells;
      CellData<2>              square;
      square.vertices    = {2, 3, 1, 0};
      square.material_id = ring_materials[0];
      cells.push_back(square);
      for (unsigned int j = 1; j < circle_radii.size(); ++j)
        for (unsigned int k = 0; k < 4; ++k)
          {
            // Clockwise along the ring, then outward: a positive Jacobian.
            const unsigned int inner = 4 * (j - 1), outer = 4 * j;
            CellData<2>        ring;
            ring.vertices    = {inner + (k + 1) % 4,
                                inner + k,
                                outer + (k + 1) % 4,
                                outer + k};
            ring.material_id = ring_materials[j];
            cells.push_back(ring);
          }
      section.create_triangulation(vertices, cells, SubCellData());
    }

    /**
     * Extrude the cross-section along x over [0, length], set boundary ids
     * (lateral, x = 0, x = length) and the manifolds: cylindrical on every
     * cell outside the lumen's core and on the lumen's circle, transfinite
     * interpolation for the lumen cells that blend square and circle.
     */
    void
    create_capillary(Triangulation<3>                      &triangulation,
                     const std::vector<double>             &radii,
                     const std::vector<types::material_id> &ring_materials,
                     const double                           length,
                     const types::boundary_id               lateral_id,
                     const types::boundary_id               start_id,
                     const types::boundary_id               end_id)
    {
      Triangulation<2> section;
      create_cross_section(section, radii, ring_materials);

      // Axial cells about half the lumen radius long, like the section's.
      const unsigned int n_layers =
        std::max(1, static_cast<int>(std::round(length / (0.5 * radii[0]))));
      GridGenerator::extrude_triangulation(section,
                                           n_layers + 1,
                                           length,
                                           triangulation);
      // A cyclic permutation of the axes (a rotation): extrusion axis z -> x.
      GridTools::transform(
        [](const Point<3> &p) { return Point<3>(p[2], p[0], p[1]); },
        triangulation);

      const double lumen_radius = radii[0];
      const double tolerance    = 1e-10 * (length + radii.back());
      const auto   on_circle    = [&](const auto &object, const double r) {
        for (const unsigned int v : object->vertex_indices())
          if (std::abs(distance_from_axis(object->vertex(v)) - r) > tolerance)
            return false;
        return true;
      };

      for (const auto &cell : triangulation.active_cell_iterators())
        {
          for (const auto &face : cell->face_iterators())
            if (face->at_boundary())
              {
                const double x = face->center()[0];
                face->set_boundary_id(x < tolerance          ? start_id :
                                      x > length - tolerance ? end_id :
                                                               lateral_id);
              }

          bool outside_core = true;
          for (const unsigned int v : cell->vertex_indices())
            if (distance_from_axis(cell->vertex(v)) < lumen_radius - tolerance)
              outside_core = false;
          if (outside_core)
            cell->set_all_manifold_ids(cylindrical_manifold_id);
          else
            cell->set_manifold_id(transfinite_manifold_id);
        }
      for (const auto &cell : triangulation.active_cell_iterators())
        if (cell->manifold_id() == transfinite_manifold_id)
          for (const auto &face : cell->face_iterators())
            if (on_circle(face, lumen_radius))
              face->set_all_manifold_ids(cylindrical_manifold_id);

      attach_capillary_manifolds(triangulation);
    }
  } // namespace

  void
  attach_capillary_manifolds(Triangulation<3> &triangulation)
  {
    triangulation.set_manifold(
      cylindrical_manifold_id,
      CylindricalManifold<3>(Tensor<1, 3>({1., 0., 0.}), Point<3>()));
    TransfiniteInterpolationManifold<3> transfinite;
    transfinite.initialize(triangulation);
    triangulation.set_manifold(transfinite_manifold_id, transfinite);
  }

  void
  create_capillary_mesh(
    parallel::fullydistributed::Triangulation<3>      &triangulation,
    const TriangulationDescription::Description<3, 3> &description)
  {
    // The description holds the coarse cells; the finer levels are made by
    // refinement, which places the new vertices on the manifolds. The
    // transfinite one is built from the coarse cells and their manifold
    // ids, so it is attached when they are all there: at the first
    // refinement, or after the creation if there is none.
    // Every boundary face of the coarse cells is a partition edge until the
    // description gives the capillary's boundaries their ids (deal.II's
    // default, 0, would make them the alveolar surface).
    const boost::signals2::scoped_connection mark =
      triangulation.signals.create.connect([&triangulation]() {
        for (const auto &cell : triangulation.cell_iterators_on_level(0))
          for (const auto &face : cell->face_iterators())
            if (face->at_boundary())
              face->set_boundary_id(partition_edge);
      });
    const boost::signals2::scoped_connection attach =
      triangulation.signals.pre_refinement.connect([&triangulation]() {
        if (triangulation.n_levels() == 1)
          attach_capillary_manifolds(triangulation);
      });
    triangulation.create_triangulation(description);
    if (triangulation.n_levels() == 1)
      attach_capillary_manifolds(triangulation);
  }

  void
  create_fluid_mesh(Triangulation<3>         &triangulation,
                    const GeometryParameters &geometry,
                    const unsigned int        n_global_refinements)
  {
    create_capillary(triangulation,
                     {geometry.capillary_radius},
                     {Material::plasma, Material::plasma},
                     geometry.capillary_length,
                     FluidBoundary::wall,
                     FluidBoundary::inlet,
                     FluidBoundary::outlet);
    triangulation.refine_global(n_global_refinements);
  }

  void
  create_diffusion_mesh(Triangulation<3>         &triangulation,
                        const GeometryParameters &geometry,
                        const unsigned int        n_global_refinements)
  {
    const double wall_radius =
      geometry.capillary_radius + geometry.wall_thickness;
    create_capillary(triangulation,
                     {geometry.capillary_radius,
                      wall_radius,
                      wall_radius + geometry.gas_layer_thickness},
                     {Material::plasma,
                      Material::plasma,
                      Material::vessel_wall,
                      Material::gas},
                     geometry.capillary_length,
                     DiffusionBoundary::alveolar_surface,
                     DiffusionBoundary::inlet_end,
                     DiffusionBoundary::outlet_end);
    triangulation.refine_global(n_global_refinements);
  }

  void
  add_end_periodicity(Triangulation<3> &mesh)
  {
    static_assert(FluidBoundary::inlet == DiffusionBoundary::inlet_end &&
                  FluidBoundary::outlet == DiffusionBoundary::outlet_end);
    std::vector<GridTools::PeriodicFacePair<Triangulation<3>::cell_iterator>>
      ends;
    GridTools::collect_periodic_faces(mesh,
                                      FluidBoundary::inlet,
                                      FluidBoundary::outlet,
                                      /*direction=*/0,
                                      ends);
    mesh.add_periodicity(ends);
  }

  namespace
  {
    using MeshCell = Triangulation<3>::cell_iterator;

    /**
     * Flag for refinement each active cell on face @p fa of @p a's subtree
     * whose image on face @p fb of @p b's subtree is refined, and the other
     * way round; whether any was flagged.
     */
    bool
    flag_coarser_end(const MeshCell    &a,
                     const unsigned int fa,
                     const MeshCell    &b,
                     const unsigned int fb)
    {
      if (a->has_children() && b->has_children())
        {
          bool flagged = false;
          for (unsigned int i = 0; i < GeometryInfo<3>::max_children_per_face;
               ++i)
            flagged |= flag_coarser_end(
              a->child(GeometryInfo<3>::child_cell_on_face(
                RefinementCase<3>::isotropic_refinement, fa, i)),
              fa,
              b->child(GeometryInfo<3>::child_cell_on_face(
                RefinementCase<3>::isotropic_refinement, fb, i)),
              fb);
          return flagged;
        }
      if (a->has_children() == b->has_children())
        return false;
      (a->has_children() ? b : a)->set_refine_flag();
      return true;
    }
  } // namespace

  void
  match_end_refinement(Triangulation<3> &mesh)
  {
    // Each round refines only where the ends differ, and the smoothing it
    // sets off may make them differ elsewhere: until nothing is flagged.
    for (;;)
      {
        std::vector<GridTools::PeriodicFacePair<MeshCell>> ends;
        GridTools::collect_periodic_faces(
          mesh, FluidBoundary::inlet, FluidBoundary::outlet, 0, ends);
        bool flagged = false;
        for (const auto &pair : ends)
          flagged |= flag_coarser_end(pair.cell[0],
                                      pair.face_idx[0],
                                      pair.cell[1],
                                      pair.face_idx[1]);
        if (!flagged)
          return;
        mesh.execute_coarsening_and_refinement();
      }
  }

  Point<3>
  wrap_into_segment(const Point<3> &p, const std::optional<double> &period)
  {
    if (!period)
      return p;
    Point<3> wrapped = p;
    wrapped[0] -= *period * std::floor(p[0] / *period);
    // floor() of a tiny negative quotient can land exactly on the period.
    if (wrapped[0] >= *period)
      wrapped[0] -= *period;
    return wrapped;
  }

  std::vector<Point<3>>
  points_in_segment(const std::vector<Point<3>> &points,
                    const std::optional<double> &period)
  {
    if (!period)
      return points;
    std::vector<Point<3>> result;
    result.reserve(3 * points.size());
    for (const Point<3> &p : points)
      for (const double shift : {0., -*period, *period})
        result.push_back(wrap_into_segment(p, period) +
                         Tensor<1, 3>({shift, 0., 0.}));
    return result;
  }

  void
  refine_near_points(Triangulation<3>            &triangulation,
                     const std::vector<Point<3>> &points,
                     const double                 band_width,
                     const unsigned int           n_steps,
                     const MeshZone              &zone)
  {
    if (points.empty())
      return;
    namespace bgi   = boost::geometry::index;
    const auto tree = pack_rtree(points);
    for (unsigned int step = 0; step < n_steps; ++step)
      {
        // After the first step only the newest, finest cells can still lie
        // in the band: a cell left alone once keeps failing the test.
        const unsigned int finest = triangulation.n_levels() - 1;
        for (const auto &cell : triangulation.active_cell_iterators())
          if ((step == 0 || cell->level() == static_cast<int>(finest)) &&
              zone.contains(cell))
            {
              const Point<3> centre = cell->center();
              for (const Point<3> &nearest :
                   tree | bgi::adaptors::queried(bgi::nearest(centre, 1)))
                if (centre.distance(nearest) <
                    band_width + 0.5 * cell->diameter())
                  cell->set_refine_flag();
            }
        triangulation.execute_coarsening_and_refinement();
      }
  }
} // namespace rbc_ifem
