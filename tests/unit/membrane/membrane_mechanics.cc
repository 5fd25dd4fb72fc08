// The membrane's energy and forces (Membrane), for both elastic laws and
// both element degrees where it matters:
//
// - the tangent stiffness K = ∂²E/∂x² of every term against the central
//   difference of the forces;
//
// - the forces are the exact negative gradient: each energy term against a
//   central finite difference along random directions at a randomly
//   perturbed shape;
// - rigid motions change no energy, and the forces have no resultant and no
//   torque;
// - the bending energy of a sphere converges to 8πκ (observed order);
// - a flat patch in homogeneous uniaxial stretch: energy W A0 and edge force
//   against the closed form of each law;
// - the area and volume of the Evans-Fung membrane converge to the exact
//   values;
// - under a uniform pressure p the volume energy holds the volume loss to
//   p/k_V, the value it alone would allow;
// - the force density (force per lumped nodal area) of a uniform pressure p
//   on a sphere is p at every node on every mesh, while the nodal force
//   shrinks with the elements.

#include <rbc_ifem/geometry/cell_surface.h>
#include <rbc_ifem/membrane/membrane.h>
#include <rbc_ifem/membrane/membrane_equilibrium.h>

#include "check.h"
#include "membrane_fixtures.h"

#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/manifold_lib.h>

#include <cmath>
#include <functional>
#include <random>

using namespace rbc_ifem;
using test::create_cell;
using test::random_vector;

namespace
{
  /// The default moduli with only the terms named switched on.
  MembraneParameters
  with_terms(const std::string &law,
             const bool         bending,
             const bool         area,
             const bool         volume)
  {
    MembraneParameters p;
    p.law             = law;
    p.degree          = 1;
    p.bending_modulus = bending ? 0.2 : 0.;
    p.area_penalty    = area ? 500. : 0.;
    p.volume_penalty  = volume ? 500. : 0.;
    return p;
  }

  /**
   * dE_term/dx·v by central differences against the force of that term,
   * -(F(all) - F(all but the term))·v, at a perturbed shape.
   */
  void
  check_gradient(Checker           &check,
                 const std::string &law,
                 const unsigned int degree)
  {
    Triangulation<2, 3> surface;
    create_cell(surface, 2);
    std::mt19937 random(7);

    const std::vector<std::pair<std::string, std::array<bool, 3>>> terms{
      {"in-plane", {{false, false, false}}},
      {"bending", {{true, false, false}}},
      {"area", {{false, true, false}}},
      {"volume", {{false, false, true}}}};
    MembraneParameters base = with_terms(law, false, false, false);
    base.degree             = degree;
    const Membrane       elastic_only(surface, base);
    const Vector<double> x =
      Vector<double>(elastic_only.reference_positions()) +=
      random_vector(elastic_only.reference_positions().size(), 0.2, random);

    Vector<double> f_base(x.size());
    elastic_only.energy_and_forces(x, f_base);
    for (const auto &[name, on] : terms)
      {
        MembraneParameters p = with_terms(law, on[0], on[1], on[2]);
        p.degree             = degree;
        const Membrane membrane(surface, p);
        Vector<double> force(x.size());
        membrane.energy_and_forces(x, force);
        if (name != "in-plane")
          force -= f_base;
        const auto part = [&](const MembraneEnergy &e) {
          return name == "in-plane" ? e.in_plane :
                 name == "bending"  ? e.bending :
                 name == "area"     ? e.area :
                                      e.volume;
        };
        double worst = 0.;
        for (unsigned int trial = 0; trial < 3; ++trial)
          {
            const Vector<double> v = random_vector(x.size(), 1., random);
            const double         h = 1e-6;
            Vector<double>       plus(x), minus(x);
            plus.add(h, v);
            minus.add(-h, v);
            const double difference =
              (part(membrane.energy(plus)) - part(membrane.energy(minus))) /
              (2. * h);
            const double exact = -(force * v);
            worst =
              std::max(worst, std::abs(difference - exact) / std::abs(exact));
          }
        check.at_most(law + ", Q" + std::to_string(degree) + ", " + name +
                        ": |dE/dx·v (finite difference) + F·v| / |F·v|",
                      worst,
                      1e-6);
      }
  }

  /**
   * The tangent stiffness of each term (and of all together, with a
   * spontaneous curvature): K v against the central difference of the
   * forces, (F(x - hv) - F(x + hv))/(2h), at a perturbed shape.
   */
  void
  check_stiffness(Checker           &check,
                  const std::string &law,
                  const unsigned int degree)
  {
    Triangulation<2, 3> surface;
    create_cell(surface, 2);
    std::mt19937                                                   random(11);
    const std::vector<std::pair<std::string, std::array<bool, 3>>> terms{
      {"in-plane", {{false, false, false}}},
      {"bending", {{true, false, false}}},
      {"area", {{false, true, false}}},
      {"volume", {{false, false, true}}},
      {"all, c0 = 0.3/µm", {{true, true, true}}}};
    for (const auto &[name, on] : terms)
      {
        MembraneParameters p = with_terms(law, on[0], on[1], on[2]);
        p.degree             = degree;
        if (name.find("c0") != std::string::npos)
          p.spontaneous_curvature = 0.3;
        const Membrane       membrane(surface, p);
        const Vector<double> x =
          Vector<double>(membrane.reference_positions()) +=
          random_vector(membrane.reference_positions().size(), 0.2, random);
        MembraneStiffness K;
        membrane.stiffness(x, K);
        const Vector<double> v = random_vector(x.size(), 1., random);
        Vector<double>       Kv(x.size());
        K.vmult_add(Kv, v);

        const double   h = 1e-6;
        Vector<double> plus(x), minus(x), f_plus(x.size()), f_minus(x.size());
        plus.add(h, v);
        minus.add(-h, v);
        membrane.energy_and_forces(plus, f_plus);
        membrane.energy_and_forces(minus, f_minus);
        Vector<double> difference(f_minus);
        difference -= f_plus;
        difference /= 2. * h;
        const double norm = Kv.l2_norm();
        difference -= Kv;
        std::cout << "  " << law << ", Q" << degree << ", " << name
                  << ": |K v| " << norm << ", |K v - difference| "
                  << difference.l2_norm() << '\n';
        check.at_most(law + ", Q" + std::to_string(degree) + ", " + name +
                        ": |K v - (F(x-hv) - F(x+hv))/2h| / |K v|",
                      difference.l2_norm() / norm,
                      1e-6);
      }
  }

  /// E(Qx + b) = E(x); Σ F = 0 and Σ x × F = 0.
  void
  check_rigid_motions(Checker &check, const std::string &law)
  {
    Triangulation<2, 3> surface;
    create_cell(surface, 2);
    std::mt19937       random(3);
    MembraneParameters p    = with_terms(law, true, true, true);
    p.spontaneous_curvature = 0.3;
    const Membrane membrane(surface, p);
    Vector<double> x(membrane.reference_positions());
    x += random_vector(x.size(), 0.2, random);

    Vector<double>     force(x.size());
    const double       energy = membrane.energy_and_forces(x, force).total();
    Tensor<1, 3>       resultant, torque;
    double             largest_force = 0., largest_moment = 0.;
    const double       angle = 0.7;
    const Tensor<1, 3> shift({1.5, -2., 0.3});
    Vector<double>     moved(x.size());
    for (const auto &dofs : membrane.nodes())
      {
        Tensor<1, 3> position, f;
        for (unsigned int d = 0; d < 3; ++d)
          {
            position[d] = x[dofs[d]];
            f[d]        = force[dofs[d]];
          }
        resultant += f;
        torque += cross_product_3d(position, f);
        largest_force  = std::max(largest_force, f.norm());
        largest_moment = std::max(largest_moment, f.norm() * position.norm());
        // A rotation about (1, 1, 1)/√3, then a shift.
        const Tensor<1, 3> axis = Tensor<1, 3>({1., 1., 1.}) / std::sqrt(3.);
        const Tensor<1, 3> rotated =
          std::cos(angle) * position +
          std::sin(angle) * cross_product_3d(axis, position) +
          (1. - std::cos(angle)) * (axis * position) * axis + shift;
        for (unsigned int d = 0; d < 3; ++d)
          moved[dofs[d]] = rotated[d];
      }
    check.at_most(law + ": |E(Qx + b) - E(x)| / E(x)",
                  std::abs(membrane.energy(moved).total() - energy) / energy,
                  1e-12);
    check.at_most(law + ": |Σ F| / max |F_i|",
                  resultant.norm() / largest_force,
                  1e-11);
    check.at_most(law + ": |Σ x × F| / max |x_i × F_i|",
                  torque.norm() / largest_moment,
                  1e-11);
  }

  /// κ/2 ∫ (2H)² dA of a sphere is 8πκ whatever its radius.
  void
  check_sphere_bending(Checker &check, const unsigned int degree)
  {
    MembraneParameters p      = with_terms("neo-Hookean", true, false, false);
    p.degree                  = degree;
    const double        exact = 8. * numbers::PI * p.bending_modulus;
    std::vector<double> errors;
    std::cout << "Sphere of radius 3 µm, Q" << degree
              << ": bending energy / 8πκ\n";
    for (unsigned int refinements = 1; refinements <= 5; ++refinements)
      {
        Triangulation<2, 3> sphere;
        GridGenerator::hyper_sphere(sphere, Point<3>(), 3.);
        sphere.refine_global(refinements);
        const Membrane membrane(sphere, p);
        const double   bending =
          membrane.energy(membrane.reference_positions()).bending;
        errors.push_back(std::abs(bending - exact) / exact);
        std::cout << "  " << refinements << " refinements: " << bending / exact
                  << ", error " << errors.back();
        if (errors.size() > 1)
          std::cout << ", order "
                    << std::log2(errors[errors.size() - 2] / errors.back());
        std::cout << '\n';
      }
    check.at_least("sphere bending, Q" + std::to_string(degree) +
                     ": observed order, last level",
                   std::log2(errors[errors.size() - 2] / errors.back()),
                   1.8);
    check.at_most("sphere bending, Q" + std::to_string(degree) +
                    ": relative error, 5 refinements",
                  errors.back(),
                  1e-3);
  }

  /// ∂W/∂λ1 (the first Piola tension) of each law in closed form.
  double
  tension(const MembraneParameters &p, const double l1, const double l2)
  {
    const double G = p.shear_modulus, K = p.area_dilation_modulus;
    if (p.law == "Skalak")
      {
        const double C = (K / G - 1.) / 2.;
        return G * l1 *
               (l1 * l1 + l2 * l2 - 2. + 1. - l2 * l2 +
                C * (l1 * l1 * l2 * l2 - 1.) * l2 * l2);
      }
    const double C1 = G / 2., C2 = K - 3. * G;
    return C1 * (2. * l1 - 2. / (l1 * l1 * l1 * l2 * l2)) +
           C2 * (l1 * l2 - 1.) * l2;
  }

  /// W(λ1, λ2) of each law in closed form.
  double
  strain_energy(const MembraneParameters &p, const double l1, const double l2)
  {
    const double G = p.shear_modulus, K = p.area_dilation_modulus;
    if (p.law == "Skalak")
      {
        const double C = (K / G - 1.) / 2., I1 = l1 * l1 + l2 * l2 - 2.,
                     I2 = l1 * l1 * l2 * l2 - 1.;
        return G / 4. * (I1 * I1 + 2. * I1 - 2. * I2 + C * I2 * I2);
      }
    return G / 2. * (l1 * l1 + l2 * l2 + 1. / (l1 * l1 * l2 * l2) - 3.) +
           (K - 3. * G) / 2. * (l1 * l2 - 1.) * (l1 * l2 - 1.);
  }

  /**
   * A flat 2 µm square patch stretched homogeneously by λ1 along x, with λ2
   * from the uniaxial condition ∂W/∂λ2 = 0 (bisection on the closed form):
   * the energy is W A0, the x forces on the edge x = λ1 L add up to
   * -∂W/∂λ1 L, and those on the edge y = λ2 L to zero.
   */
  void
  check_uniaxial_stretch(Checker           &check,
                         const std::string &law,
                         const unsigned int degree)
  {
    MembraneParameters p  = with_terms(law, false, false, false);
    p.degree              = degree;
    const double        L = 2.;
    Triangulation<2, 3> patch;
    GridGenerator::hyper_cube(patch, 0., L);
    patch.refine_global(2);
    const Membrane        membrane(patch, p);
    const Vector<double> &X = membrane.reference_positions();

    for (const double l1 : {1.2, 1.6, 2.0})
      {
        double low = 0.3, high = 1.;
        for (unsigned int i = 0; i < 100; ++i)
          (tension(p, 0.5 * (low + high), l1) > 0. ? high : low) =
            0.5 * (low + high);
        const double l2 = 0.5 * (low + high);

        Vector<double> x(X);
        for (const auto &dofs : membrane.nodes())
          {
            x[dofs[0]] *= l1;
            x[dofs[1]] *= l2;
          }
        Vector<double> force(x.size());
        const double   energy = membrane.energy_and_forces(x, force).in_plane;
        double         edge_x = 0., edge_y = 0.;
        for (const auto &dofs : membrane.nodes())
          {
            if (std::abs(X[dofs[0]] - L) < 1e-12)
              edge_x += force[dofs[0]];
            if (std::abs(X[dofs[1]] - L) < 1e-12)
              edge_y += force[dofs[1]];
          }
        const std::string what = law + ", Q" + std::to_string(degree) +
                                 ", λ1 = " + std::to_string(l1).substr(0, 3);
        const double T1 = tension(p, l1, l2);
        std::cout << "  " << what << ": λ2 = " << l2 << ", tension T1 = " << T1
                  << " pN/µm (Cauchy " << T1 / l2 << ")\n";
        check.near(what + ": energy / (W A0)",
                   energy / (strain_energy(p, l1, l2) * L * L),
                   1.,
                   1e-10);
        check.near(what + ": edge force / (-T1 L)",
                   edge_x / (-T1 * L),
                   1.,
                   1e-10);
        check.at_most(what + ": |lateral edge force| / (T1 L)",
                      std::abs(edge_y) / (T1 * L),
                      1e-8);
      }
  }

  /// The discrete reference area and volume converge to the exact ones.
  void
  check_cell_measures(Checker &check, const unsigned int degree)
  {
    MembraneParameters p = with_terms("neo-Hookean", false, false, false);
    p.degree             = degree;
    const EvansFungShape shape(7.5);
    double               area_error = 0., volume_error = 0.;
    std::cout << "Evans-Fung cell, Q" << degree << ": area and volume errors\n";
    for (unsigned int refinements = 2; refinements <= 4; ++refinements)
      {
        Triangulation<2, 3> surface;
        create_cell(surface, refinements);
        const Membrane membrane(surface, p);
        const double   a =
          std::abs(membrane.reference_area() - shape.exact_area()) /
          shape.exact_area();
        const double v =
          std::abs(membrane.reference_volume() - shape.exact_volume()) /
          shape.exact_volume();
        std::cout << "  " << refinements << " refinements: area " << a;
        if (area_error > 0.)
          std::cout << " (order " << std::log2(area_error / a) << ")";
        std::cout << ", volume " << v;
        if (volume_error > 0.)
          std::cout << " (order " << std::log2(volume_error / v) << ")";
        std::cout << '\n';
        area_error   = a;
        volume_error = v;
      }
    const double bound = degree == 1 ? 5e-3 : 1e-5;
    check.at_most("Q" + std::to_string(degree) +
                    " cell, 4 refinements: relative area error",
                  area_error,
                  bound);
    check.at_most("Q" + std::to_string(degree) +
                    " cell, 4 refinements: relative volume error",
                  volume_error,
                  bound);
  }

  /**
   * A uniform inward pressure p on the cell, as dead nodal forces -p w_i
   * (w_i the nodal vector areas of the reference, the volume's gradient):
   * near the reference its work is -p ΔV, so the volume energy alone would
   * stop the loss at ΔV/V0 = -p/k_V, and the elasticity only adds
   * resistance. Without the volume energy the cell loses far more.
   */
  void
  check_volume_penalty_under_pressure(Checker &check)
  {
    Triangulation<2, 3> surface;
    create_cell(surface, 2);
    const double pressure          = 2.; // [pN/µm²]
    double       loss_with_penalty = 0.;
    for (const double k_V : {500., 0.})
      {
        MembraneParameters p = with_terms("Skalak", true, true, true);
        p.volume_penalty     = k_V;
        const Membrane membrane(surface, p);
        Vector<double> x(membrane.reference_positions()), load(x.size());
        const auto     w = membrane.nodal_vector_areas(x);
        for (unsigned int i = 0; i < w.size(); ++i)
          for (unsigned int d = 0; d < 3; ++d)
            load[membrane.nodes()[i][d]] = -pressure * w[i][d];
        const EquilibriumReport report =
          find_equilibrium(membrane, load, x, 1e-6, 20000);
        const double loss =
          1. - membrane.volume(x) / membrane.reference_volume();
        std::cout << "Cell under " << pressure << " pN/µm², k_V = " << k_V
                  << ": " << report.iterations
                  << " L-BFGS iterations, volume loss " << loss
                  << " V0, area change "
                  << membrane.area(x) / membrane.reference_area() - 1.
                  << " A0\n";
        if (k_V > 0.)
          {
            loss_with_penalty = loss;
            check.at_most("volume loss / (p/k_V) with the volume energy",
                          loss / (pressure / k_V),
                          1.);
            check.at_least("volume loss / (p/k_V) with the volume energy",
                           loss / (pressure / k_V),
                           0.9);
          }
        else
          check.at_least("volume loss without / with the volume energy",
                         loss / loss_with_penalty,
                         3.);
      }
  }
  /**
   * The nodal forces -p w_i of a pressure p on a sphere, divided by the
   * lumped nodal areas (Membrane::force_densities()): |f_i|/m_i = p up to
   * the discretisation (second order), on every mesh, where the largest
   * nodal force falls about fourfold per refinement.
   */
  void
  check_force_density(Checker &check)
  {
    const double pressure = 2.;
    std::cout << "Force per area of a pressure " << pressure
              << " pN/µm² on a sphere of radius 3 µm, Q1\n";
    double last_force = 0., last_deviation = 0.;
    for (unsigned int refinements = 2; refinements <= 4; ++refinements)
      {
        Triangulation<2, 3> sphere;
        GridGenerator::hyper_sphere(sphere, Point<3>(), 3.);
        sphere.refine_global(refinements);
        const Membrane        membrane(sphere, with_terms("Skalak", 0, 0, 0));
        const Vector<double> &x = membrane.reference_positions();
        const auto            w = membrane.nodal_vector_areas(x);
        Vector<double>        f(x.size());
        for (unsigned int i = 0; i < w.size(); ++i)
          for (unsigned int d = 0; d < 3; ++d)
            f[membrane.nodes()[i][d]] = -pressure * w[i][d];
        const Vector<double> density   = membrane.force_densities(x, f);
        double               deviation = 0., largest_force = 0.;
        for (const auto &node : membrane.nodes())
          {
            Tensor<1, 3> force, traction;
            for (unsigned int d = 0; d < 3; ++d)
              {
                force[d]    = f[node[d]];
                traction[d] = density[node[d]];
              }
            deviation =
              std::max(deviation, std::abs(traction.norm() / pressure - 1.));
            largest_force = std::max(largest_force, force.norm());
          }
        std::cout << "  " << refinements << " refinements: largest |f_i| "
                  << largest_force << " pN, largest ||f_i|/m_i/p - 1| "
                  << deviation << '\n';
        check.at_most("force density / p - 1, " + std::to_string(refinements) +
                        " refinements",
                      deviation,
                      0.04);
        if (last_force > 0.)
          {
            check.at_least("nodal force falls per refinement",
                           last_force / largest_force,
                           3.);
            check.at_least("force density: observed order",
                           std::log2(last_deviation / deviation),
                           1.8);
          }
        last_force     = largest_force;
        last_deviation = deviation;
      }
  }
} // namespace

int
main()
{
  Checker check;
  for (const std::string law : {"neo-Hookean", "Skalak"})
    for (const unsigned int degree : {1u, 2u})
      {
        check_gradient(check, law, degree);
        check_stiffness(check, law, degree);
      }
  for (const std::string law : {"neo-Hookean", "Skalak"})
    check_rigid_motions(check, law);
  for (const unsigned int degree : {1u, 2u})
    check_sphere_bending(check, degree);
  std::cout << "Uniaxial stretch of a flat patch\n";
  for (const std::string law : {"neo-Hookean", "Skalak"})
    for (const unsigned int degree : {1u, 2u})
      check_uniaxial_stretch(check, law, degree);
  for (const unsigned int degree : {1u, 2u})
    check_cell_measures(check, degree);
  check_volume_penalty_under_pressure(check);
  check_force_density(check);
  return check.exit_code();
}
