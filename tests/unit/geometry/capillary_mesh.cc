// The capillary meshes: volume of each material region and area of each
// boundary id against the exact cylinder values, with the error falling at
// the expected rate under refinement; band refinement refines exactly the
// cells near the given points.

#include <rbc_ifem/geometry/capillary_mesh.h>

#include "check.h"

#include <deal.II/base/quadrature_lib.h>
#include <deal.II/fe/fe_nothing.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/fe/mapping_q.h>

#include <map>

using namespace rbc_ifem;

namespace
{
  struct Measures
  {
    std::map<types::material_id, double> volume;
    std::map<types::boundary_id, double> area;
  };

  Measures
  measure(const Triangulation<3> &triangulation)
  {
    const MappingQ<3>   mapping(2);
    const FE_Nothing<3> fe;
    FEValues<3>         fe_values(mapping, fe, QGauss<3>(4), update_JxW_values);
    FEFaceValues<3> face_values(mapping, fe, QGauss<2>(4), update_JxW_values);
    Measures        m;
    for (const auto &cell : triangulation.active_cell_iterators())
      {
        fe_values.reinit(cell);
        for (const unsigned int q : fe_values.quadrature_point_indices())
          m.volume[cell->material_id()] += fe_values.JxW(q);
        for (const unsigned int f : cell->face_indices())
          if (cell->face(f)->at_boundary())
            {
              face_values.reinit(cell, f);
              for (const unsigned int q :
                   face_values.quadrature_point_indices())
                m.area[cell->face(f)->boundary_id()] += face_values.JxW(q);
            }
      }
    return m;
  }

  /**
   * Relative errors of all measured quantities against @p exact, on
   * successive refinements; checks the error at the finest level and the
   * observed order between the last two.
   */
  void
  convergence_study(
    Checker                                                     &check,
    const std::string                                           &mesh_name,
    const std::function<void(Triangulation<3> &, unsigned int)> &create,
    const std::map<std::string, double>                         &exact,
    const std::function<std::map<std::string, double>(const Measures &)>
                      &extract,
    const unsigned int finest,
    const double       tolerance,
    const double       minimum_order)
  {
    std::map<std::string, double> previous_error;
    std::cout << mesh_name << ": relative errors (observed order)\n";
    for (unsigned int level = 0; level <= finest; ++level)
      {
        Triangulation<3> triangulation;
        create(triangulation, level);
        const auto measured = extract(measure(triangulation));
        std::cout << "  level " << level << ", "
                  << triangulation.n_active_cells() << " cells:";
        std::map<std::string, double> error;
        for (const auto &[name, value] : exact)
          {
            error[name] = std::abs(measured.at(name) - value) / value;
            std::cout << "  " << name << ' ' << std::scientific
                      << std::setprecision(2) << error[name];
            if (level > 0)
              std::cout << " (" << std::fixed << std::setprecision(2)
                        << std::log2(previous_error[name] / error[name]) << ')';
          }
        std::cout << '\n';
        if (level == finest)
          for (const auto &[name, e] : error)
            {
              check.at_most(mesh_name + ": relative error of " + name,
                            e,
                            tolerance);
              check.at_least(mesh_name + ": observed order of " + name,
                             std::log2(previous_error[name] / e),
                             minimum_order);
            }
        previous_error = error;
      }
  }
} // namespace

int
main()
{
  Checker                  check;
  const GeometryParameters g; // R = 5, L = 20, wall 1, gas 5 µm
  const double pi = numbers::PI, R = g.capillary_radius, L = g.capillary_length;
  const double R_wall = R + g.wall_thickness,
               R_gas  = R_wall + g.gas_layer_thickness;

  convergence_study(
    check,
    "fluid mesh",
    [&](Triangulation<3> &t, unsigned int level) {
      create_fluid_mesh(t, g, level);
    },
    {{"lumen volume", pi * R * R * L},
     {"inlet area", pi * R * R},
     {"outlet area", pi * R * R},
     {"wall area", 2. * pi * R * L}},
    [](const Measures &m) {
      return std::map<std::string, double>{
        {"lumen volume", m.volume.at(Material::plasma)},
        {"inlet area", m.area.at(FluidBoundary::inlet)},
        {"outlet area", m.area.at(FluidBoundary::outlet)},
        {"wall area", m.area.at(FluidBoundary::wall)}};
    },
    3,
    1e-5,
    3.5);

  convergence_study(
    check,
    "diffusion mesh",
    [&](Triangulation<3> &t, unsigned int level) {
      create_diffusion_mesh(t, g, level);
    },
    {{"plasma volume", pi * R * R * L},
     {"wall volume", pi * (R_wall * R_wall - R * R) * L},
     {"gas volume", pi * (R_gas * R_gas - R_wall * R_wall) * L},
     {"alveolar area", 2. * pi * R_gas * L},
     {"end area", pi * R_gas * R_gas}},
    [](const Measures &m) {
      return std::map<std::string, double>{
        {"plasma volume", m.volume.at(Material::plasma)},
        {"wall volume", m.volume.at(Material::vessel_wall)},
        {"gas volume", m.volume.at(Material::gas)},
        {"alveolar area", m.area.at(DiffusionBoundary::alveolar_surface)},
        {"end area", m.area.at(DiffusionBoundary::inlet_end)}};
    },
    3,
    1e-5,
    3.5);

  // Band refinement: exactly the cells closer than the band to the points
  // are refined once more, all others keep their level.
  {
    Triangulation<3> triangulation;
    create_fluid_mesh(triangulation, g, 1);
    const std::vector<Point<3>> points{Point<3>(10., 0., 0.),
                                       Point<3>(10., 2., 0.)};
    const double                band = 0.5;
    std::vector<bool> expected_refined(triangulation.n_active_cells());
    for (const auto &cell : triangulation.active_cell_iterators())
      for (const Point<3> &p : points)
        if (cell->center().distance(p) < band + 0.5 * cell->diameter())
          expected_refined[cell->active_cell_index()] = true;
    for (const auto &cell : triangulation.active_cell_iterators())
      cell->set_user_index(cell->active_cell_index());
    refine_near_points(triangulation, points, band, 1);
    unsigned int wrong = 0, refined = 0;
    for (const auto &cell : triangulation.active_cell_iterators())
      {
        const bool is_child = cell->level() == 2;
        // A refined cell keeps the user index it had while active.
        const unsigned int index =
          is_child ? cell->parent()->user_index() : cell->user_index();
        const bool expected = expected_refined[index];
        // Refinement may add cells to keep one hanging node per face; it never
        // leaves an expected cell unrefined.
        if (expected && !is_child)
          ++wrong;
        refined += is_child;
      }
    check.holds("band refinement refines every cell near the points",
                wrong == 0);
    check.at_least("children created by band refinement", refined, 8.);
  }
  return check.exit_code();
}
