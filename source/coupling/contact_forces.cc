#include <rbc_ifem/coupling/cell_boxes.h>
#include <rbc_ifem/coupling/cell_population.h>
#include <rbc_ifem/coupling/contact_forces.h>
#include <rbc_ifem/coupling/point_bins.h>
#include <rbc_ifem/coupling/point_forces.h>
#include <rbc_ifem/geometry/capillary_mesh.h>
#include <rbc_ifem/membrane/membrane_equilibrium.h>

#include <cmath>
#include <limits>
#include <tuple>

namespace rbc_ifem
{
  namespace
  {
    /**
     * K of point forces: 3 × 3 blocks on single points (a wall) and on
     * pairs of points i, j whose energy depends on x_i - x_j (K_ii = K_jj =
     * H, K_ij = K_ji = -H), in the rows of the cells this rank owns.
     */
    class PointBlockStiffness : public CellForceStiffness
    {
    public:
      explicit PointBlockStiffness(const CellOwners &owners)
        : owners(owners)
      {}

      /// A point: its cell and its node's DoFs.
      using PointDoFs =
        std::pair<unsigned int, std::array<types::global_dof_index, 3>>;

      void
      add_product(const std::vector<Vector<double>> &v,
                  std::vector<Vector<double>>       &results) const override
      {
        const auto at = [&](const PointDoFs &point) {
          const auto &[c, dofs] = point;
          return Tensor<1, 3>({v[c][dofs[0]], v[c][dofs[1]], v[c][dofs[2]]});
        };
        const auto add = [&](const PointDoFs &point, const Tensor<1, 3> &f) {
          const auto &[c, dofs] = point;
          if (owners.owns(c))
            for (unsigned int d = 0; d < 3; ++d)
              results[c][dofs[d]] += f[d];
        };
        for (const auto &[point, H] : single)
          add(point, H * at(point));
        for (const auto &[i, j, H] : pairs)
          {
            const Tensor<1, 3> f = H * (at(i) - at(j));
            add(i, f);
            add(j, -f);
          }
      }

      void
      add_diagonal(std::vector<Vector<double>> &diagonal) const override
      {
        const auto add = [&](const PointDoFs &point, const Tensor<2, 3> &H) {
          const auto &[c, dofs] = point;
          if (owners.owns(c))
            for (unsigned int d = 0; d < 3; ++d)
              diagonal[c][dofs[d]] += H[d][d];
        };
        for (const auto &[point, H] : single)
          add(point, H);
        for (const auto &[i, j, H] : pairs)
          {
            add(i, H);
            add(j, H);
          }
      }

      void
      mark_cells_read(std::vector<bool> &cells) const override
      {
        for (const auto &[i, j, H] : pairs)
          {
            cells[i.first] = true;
            cells[j.first] = true;
          }
      }

      std::vector<std::pair<PointDoFs, Tensor<2, 3>>>             single;
      std::vector<std::tuple<PointDoFs, PointDoFs, Tensor<2, 3>>> pairs;

    private:
      /// A copy: the owners when K was taken.
      const CellOwners owners;
    };
  } // namespace

  RepulsivePotential::RepulsivePotential(const double pressure_scale,
                                         const double range)
    : p0(pressure_scale)
    , range(range)
  {}

  double
  RepulsivePotential::cutoff() const
  {
    return range;
  }

  double
  RepulsivePotential::energy(const double h) const
  {
    if (h >= range)
      return 0.;
    // φ(h) = ∫_h^Δ p0 (Δ/s - 1)² ds.
    return p0 * (range * range * (1. / h - 1. / range) -
                 2. * range * std::log(range / h) + (range - h));
  }

  std::pair<double, double>
  RepulsivePotential::pressure(const double h) const
  {
    const double excess = range / h - 1.;
    return {p0 * excess * excess, -2. * p0 * excess * range / (h * h)};
  }

  double
  RepulsivePotential::pressure_curvature(const double h) const
  {
    const double excess = range / h - 1.;
    return 2. * p0 * range * range / std::pow(h, 4) +
           4. * p0 * excess * range / std::pow(h, 3);
  }

  MorsePotential::MorsePotential(const double well_depth,
                                 const double width,
                                 const double distance,
                                 const double cutoff)
    : depth(well_depth)
    , beta(width)
    , distance(distance)
    , gap_cutoff(cutoff)
  {}

  double
  MorsePotential::cutoff() const
  {
    return gap_cutoff;
  }

  double
  MorsePotential::energy(const double h) const
  {
    const auto phi = [this](const double gap) {
      const double e = std::exp(beta * (distance - gap));
      return depth * (e * e - 2. * e);
    };
    return h < gap_cutoff ? phi(h) - phi(gap_cutoff) : 0.;
  }

  std::pair<double, double>
  MorsePotential::pressure(const double h) const
  {
    const double e = std::exp(beta * (distance - h));
    return {2. * beta * depth * (e * e - e),
            2. * beta * beta * depth * (e - 2. * e * e)};
  }

  double
  MorsePotential::pressure_curvature(const double h) const
  {
    const double e = std::exp(beta * (distance - h));
    return 2. * beta * beta * beta * depth * (4. * e * e - e);
  }

  MembraneInteraction::MembraneInteraction(
    const std::vector<std::shared_ptr<Membrane>> &membranes,
    std::unique_ptr<GapPotential>                 potential,
    const std::optional<double>                  &period,
    const CellOwners                             &owners)
    : membranes(membranes)
    , potential(std::move(potential))
    , period(period)
    , owners(owners)
    , reference_areas(reference_point_areas(membranes))
    , at_cutoff(unshifted_pair_density(this->potential->cutoff()))
  {}

  std::pair<double, double>
  MembraneInteraction::unshifted_pair_density(const double r) const
  {
    const auto [p, dp]  = potential->pressure(r);
    const double two_pi = 2. * numbers::PI;
    return {p / (two_pi * r), (dp * r - p) / (two_pi * r * r)};
  }

  std::pair<double, double>
  MembraneInteraction::pair_density(const double r) const
  {
    const auto [psi, dpsi] = unshifted_pair_density(r);
    const double rc        = potential->cutoff();
    return {psi - at_cutoff.first - at_cutoff.second * (r - rc),
            dpsi - at_cutoff.second};
  }

  double
  MembraneInteraction::pair_density_curvature(const double r) const
  {
    // ψ = p/(2πr): ψ'' = (p'' r² - 2 p' r + 2 p)/(2π r³).
    const auto [p, dp] = potential->pressure(r);
    const double d2p   = potential->pressure_curvature(r);
    return (d2p * r * r - 2. * dp * r + 2. * p) /
           (2. * numbers::PI * r * r * r);
  }

  template <typename PairFunction>
  void
  MembraneInteraction::for_each_close_pair(const std::vector<Vector<double>> &x,
                                           const PairFunction &f) const
  {
    // Every point of this rank's cells and of the cells near them (its
    // ghosts) with its cell and node, in one list for the bins: in a
    // periodic segment each where it lies in the segment, and those within
    // the cutoff of its end once more one period before its start. A pair
    // across the ends is then found once, as a point and an image.
    const double            cutoff = potential->cutoff();
    const std::vector<bool> near =
      CellBoxes(membranes, x, period).near_owned(owners, cutoff);
    std::vector<Point<3>>                              points;
    std::vector<std::pair<unsigned int, unsigned int>> owner;
    std::vector<bool>                                  image;
    for (const bool images : {false, true})
      for (unsigned int c = 0; c < membranes.size(); ++c)
        if (near[c])
          {
            const auto &nodes = membranes[c]->nodes();
            for (unsigned int n = 0; n < nodes.size(); ++n)
              {
                Point<3> p =
                  wrap_into_segment(node_position(x[c], nodes[n]), period);
                if (images)
                  {
                    if (!period || p[0] < *period - cutoff)
                      continue;
                    p[0] -= *period;
                  }
                points.push_back(p);
                owner.emplace_back(c, n);
                image.push_back(images);
              }
          }

    PointBins(points, cutoff)
      .for_each_close_pair([&](const unsigned int i, const unsigned int j) {
        const auto [ci, ni] = owner[i];
        const auto [cj, nj] = owner[j];
        if (ci == cj || (image[i] && image[j]) ||
            !(owners.owns(ci) || owners.owns(cj)))
          return;
        const Tensor<1, 3> separation = points[i] - points[j];
        f(ClosePair{ci,
                    ni,
                    cj,
                    nj,
                    separation,
                    separation.norm(),
                    reference_areas[ci][ni] * reference_areas[cj][nj]});
      });
  }

  CellForceReport
  MembraneInteraction::add_forces(const std::vector<Vector<double>> &x,
                                  std::vector<Vector<double>> &forces) const
  {
    // A pair of two ranks' cells is found by both: each takes the force on
    // its own point and half the energy.
    CellForceReport report;
    for_each_close_pair(x, [&](const ClosePair &pair) {
      const auto [psi, dpsi] = pair_density(pair.r);
      const bool owns_i      = owners.owns(pair.ci);
      const bool owns_j      = owners.owns(pair.cj);
      report.energy += (owns_i && owns_j ? 1. : 0.5) * pair.weight * psi;
      const Tensor<1, 3> force = -pair.weight * dpsi / pair.r * pair.separation;
      if (owns_i)
        add_node_force(forces[pair.ci],
                       membranes[pair.ci]->nodes()[pair.ni],
                       force);
      if (owns_j)
        add_node_force(forces[pair.cj],
                       membranes[pair.cj]->nodes()[pair.nj],
                       -force);
    });
    return report;
  }

  std::unique_ptr<CellForceStiffness>
  MembraneInteraction::stiffness(const std::vector<Vector<double>> &x) const
  {
    // E = w ψ(r): ∂²E/∂x_i² = w [ψ'' n nᵀ + ψ'/r (I - n nᵀ)], n = (x_i -
    // x_j)/r, and the opposite on the pair's cross terms.
    auto result = std::make_unique<PointBlockStiffness>(owners);
    for_each_close_pair(x, [&](const ClosePair &pair) {
      const Tensor<1, 3> n      = pair.separation / pair.r;
      const double       dpsi   = pair_density(pair.r).second;
      const Tensor<2, 3> normal = outer_product(n, n);
      Tensor<2, 3>       identity;
      for (unsigned int d = 0; d < 3; ++d)
        identity[d][d] = 1.;
      const Tensor<2, 3> H =
        pair.weight * (pair_density_curvature(pair.r) * normal +
                       dpsi / pair.r * (identity - normal));
      result->pairs.emplace_back(
        PointBlockStiffness::PointDoFs(pair.ci,
                                       membranes[pair.ci]->nodes()[pair.ni]),
        PointBlockStiffness::PointDoFs(pair.cj,
                                       membranes[pair.cj]->nodes()[pair.nj]),
        H);
    });
    return result;
  }

  WallRepulsion::WallRepulsion(
    const std::vector<std::shared_ptr<Membrane>> &membranes,
    const double                                  radius,
    const RepulsivePotential                     &potential,
    const CellOwners                             &owners)
    : membranes(membranes)
    , radius(radius)
    , potential(potential)
    , owners(owners)
    , reference_areas(reference_point_areas(membranes))
  {}

  CellForceReport
  WallRepulsion::add_forces(const std::vector<Vector<double>> &x,
                            std::vector<Vector<double>>       &forces) const
  {
    CellForceReport report;
    for (unsigned int c = 0; c < membranes.size(); ++c)
      if (owners.owns(c))
        {
          const CellForceReport cell =
            add_cell_forces(c, radius, x[c], forces[c]);
          report.energy += cell.energy;
          report.external_force += cell.external_force;
        }
    return report;
  }

  CellForceReport
  WallRepulsion::add_cell_forces(const unsigned int    c,
                                 const double          wall_radius,
                                 const Vector<double> &x,
                                 Vector<double>       &forces) const
  {
    CellForceReport report;
    const auto     &nodes = membranes[c]->nodes();
    for (unsigned int n = 0; n < nodes.size(); ++n)
      {
        const Point<3> p    = node_position(x, nodes[n]);
        const double   rho  = std::hypot(p[1], p[2]);
        const double   gap  = wall_radius - rho;
        const double   area = reference_areas[c][n];
        if (gap >= potential.cutoff())
          continue;
        if (gap <= 0.)
          {
            report.energy = std::numeric_limits<double>::infinity();
            continue;
          }
        report.energy += area * potential.energy(gap);
        // F = -a φ'(d) ∂d/∂x = a p(d) ∂d/∂x, with ∂d/∂x = -(0, y, z)/ρ.
        const double pressure = potential.pressure(gap).first;
        Tensor<1, 3> force;
        force[1] = -area * pressure * p[1] / rho;
        force[2] = -area * pressure * p[2] / rho;
        add_node_force(forces, nodes[n], force);
        report.external_force += force;
      }
    return report;
  }

  std::unique_ptr<CellForceStiffness>
  WallRepulsion::stiffness(const std::vector<Vector<double>> &x) const
  {
    // E = a φ(d), d = R - ρ: ∇d = -e (e = (0, y, z)/ρ), ∂²d = -(P - e eᵀ)/ρ
    // with P the projection on y, z; φ' = -p, φ'' = -p'.
    auto result = std::make_unique<PointBlockStiffness>(owners);
    for (unsigned int c = 0; c < membranes.size(); ++c)
      if (owners.owns(c))
        {
          const auto &nodes = membranes[c]->nodes();
          for (unsigned int n = 0; n < nodes.size(); ++n)
            {
              const Point<3> p   = node_position(x[c], nodes[n]);
              const double   rho = std::hypot(p[1], p[2]);
              const double   gap = radius - rho;
              if (gap >= potential.cutoff() || gap <= 0.)
                continue;
              const auto [pressure, dp] = potential.pressure(gap);
              const Tensor<1, 3> e({0., p[1] / rho, p[2] / rho});
              Tensor<2, 3>       plane;
              plane[1][1] = plane[2][2] = 1.;
              const Tensor<2, 3> radial = outer_product(e, e);
              result->single.emplace_back(
                PointBlockStiffness::PointDoFs(c, nodes[n]),
                reference_areas[c][n] *
                  (-dp * radial + pressure / rho * (plane - radial)));
            }
        }
    return result;
  }

  unsigned int
  WallRepulsion::squeeze_into_lumen(std::vector<Vector<double>> &x) const
  {
    // Each cell is squeezed alone, by its owner, along the same path as
    // on one rank; the others' positions are zero here until the sum.
    double stages = 0.;
    for (unsigned int c = 0; c < membranes.size(); ++c)
      {
        if (!owners.owns(c))
          {
            x[c] = 0.;
            continue;
          }
        const auto widest = [&]() {
          double rho = 0.;
          for (const auto &dofs : membranes[c]->nodes())
            rho = std::max(rho, std::hypot(x[c][dofs[1]], x[c][dofs[2]]));
          return rho;
        };
        // The wall starts just outside the cell and closes in on it by half
        // the smallest gap at a time, each time to the membrane's static
        // equilibrium against it, until it stands at the capillary's.
        double wall = std::max(radius, widest() + 0.5 * potential.cutoff());
        while (wall > radius)
          {
            wall = std::max(radius, wall - 0.5 * (wall - widest()));
            if (wall - radius < 1e-3 * potential.cutoff())
              wall = radius;
            find_equilibrium(
              *membranes[c],
              [&, wall](const Vector<double> &positions,
                        Vector<double>       &forces) {
                return add_cell_forces(c, wall, positions, forces).energy;
              },
              x[c],
              /*tolerance [pN]=*/1e-2,
              /*max_iterations=*/5000);
            ++stages;
          }
      }
    owners.add_up(x, make_array_view(&stages, &stages + 1));
    return static_cast<unsigned int>(stages);
  }

  std::vector<std::unique_ptr<GapPotential>>
  cell_potentials(const InteractionParameters &parameters)
  {
    std::vector<std::unique_ptr<GapPotential>> potentials;
    if (parameters.repulsion_pressure > 0.)
      potentials.push_back(
        std::make_unique<RepulsivePotential>(parameters.repulsion_pressure,
                                             parameters.repulsion_range));
    if (parameters.aggregation)
      potentials.push_back(
        std::make_unique<MorsePotential>(parameters.aggregation_energy,
                                         parameters.aggregation_width,
                                         parameters.aggregation_distance,
                                         parameters.aggregation_cutoff));
    return potentials;
  }

  double
  contact_reach(const InteractionParameters &parameters)
  {
    double reach = 0.;
    for (const auto &potential : cell_potentials(parameters))
      reach = std::max(reach, potential->cutoff());
    return reach;
  }

  void
  add_interaction_forces(CellPopulation              &cells,
                         const InteractionParameters &parameters,
                         const std::optional<double>  wall_radius,
                         const std::optional<double>  period)
  {
    if (cells.size() > 1)
      for (auto &potential : cell_potentials(parameters))
        cells.add_force(std::make_unique<MembraneInteraction>(
          cells.membranes(), std::move(potential), period, cells.owners()));
    if (parameters.wall_pressure > 0. && wall_radius)
      cells.add_force(std::make_unique<WallRepulsion>(
        cells.membranes(),
        *wall_radius,
        RepulsivePotential(parameters.wall_pressure, parameters.wall_range),
        cells.owners()));
  }
} // namespace rbc_ifem
