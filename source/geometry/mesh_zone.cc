#include <rbc_ifem/geometry/mesh_zone.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <set>

namespace rbc_ifem
{
  namespace
  {
    /// The smallest and largest x of @p cell's vertices.
    std::pair<double, double>
    x_extent(const Triangulation<3>::cell_iterator &cell)
    {
      double low = cell->vertex(0)[0], high = low;
      for (const unsigned int v : cell->vertex_indices())
        {
          low  = std::min(low, cell->vertex(v)[0]);
          high = std::max(high, cell->vertex(v)[0]);
        }
      return {low, high};
    }

    /**
     * Per coarse cell, its slab: the cells in @p order (along x) cut into
     * @p n_ranks runs of about equal weight, each cell in the run where its
     * preceding weight falls (unit weights if @p weights is empty).
     */
    std::vector<unsigned int>
    slabs(const std::vector<unsigned int> &order,
          const unsigned int               n_ranks,
          const std::vector<double>       &weights)
    {
      const auto weight = [&weights](const unsigned int c) {
        return weights.empty() ? 1. : weights[c];
      };
      double total = 0.;
      for (const unsigned int c : order)
        total += weight(c);
      std::vector<unsigned int> slab_of(order.size());
      double                    before = 0.;
      for (const unsigned int c : order)
        {
          // Integer weights are summed and divided exactly: with unit
          // weights, position k goes to slab k P / C, rounded down.
          slab_of[c] = std::min(n_ranks - 1,
                                static_cast<unsigned int>(
                                  std::floor(before * n_ranks / total)));
          before += weight(c);
        }
      return slab_of;
    }
  } // namespace

  MeshZone::MeshZone(const Triangulation<3>      &coarse,
                     const unsigned int           rank,
                     const unsigned int           n_ranks,
                     const std::optional<double> &period,
                     const std::vector<double>   &weights)
    : rank(rank)
  {
    const unsigned int                     n_cells = coarse.n_cells(0);
    std::vector<std::pair<double, double>> extents;
    std::vector<double>                    centres;
    for (const auto &cell : coarse.cell_iterators_on_level(0))
      {
        extents.push_back(x_extent(cell));
        centres.push_back(cell->center()[0]);
      }
    std::vector<unsigned int> order(n_cells);
    std::iota(order.begin(), order.end(), 0u);
    std::stable_sort(order.begin(),
                     order.end(),
                     [&](const unsigned int a, const unsigned int b) {
                       return centres[a] < centres[b];
                     });
    slab_of = slabs(order, n_ranks, weights);
    if (std::set<unsigned int>(slab_of.begin(), slab_of.end()).size() <
        std::min<std::size_t>(n_ranks, n_cells))
      // A coarse cell heavier than a rank's share left a rank without one.
      slab_of = slabs(order, n_ranks, {});

    // The slab's x range, widened by two of the longest coarse cells.
    double longest = 0., low = 0., high = 0.;
    bool   any = false;
    for (unsigned int c = 0; c < n_cells; ++c)
      {
        longest = std::max(longest, extents[c].second - extents[c].first);
        if (slab_of[c] == rank)
          {
            low  = any ? std::min(low, extents[c].first) : extents[c].first;
            high = any ? std::max(high, extents[c].second) : extents[c].second;
            any  = true;
          }
      }
    const double margin = 2. * longest + 1e-9 * (high - low + longest);
    in_zone.assign(n_cells, false);
    for (unsigned int c = 0; c < n_cells; ++c)
      for (const double shift : period ?
                                  std::vector<double>{0., -*period, *period} :
                                  std::vector<double>{0.})
        if (any && extents[c].first + shift < high + margin &&
            extents[c].second + shift > low - margin)
          in_zone[c] = true;
  }

  bool
  MeshZone::contains(const Triangulation<3>::cell_iterator &cell) const
  {
    return in_zone.empty() || in_zone[cell->id().get_coarse_cell_id()];
  }

  unsigned int
  MeshZone::owner(const Triangulation<3>::cell_iterator &cell) const
  {
    return slab_of.empty() ? 0 : slab_of[cell->id().get_coarse_cell_id()];
  }

  void
  MeshZone::refine_global(Triangulation<3>  &mesh,
                          const unsigned int times) const
  {
    if (in_zone.empty())
      {
        mesh.refine_global(times);
        return;
      }
    for (unsigned int step = 0; step < times; ++step)
      {
        for (const auto &cell : mesh.active_cell_iterators())
          if (contains(cell))
            cell->set_refine_flag();
        mesh.execute_coarsening_and_refinement();
      }
  }

  MeshZone
  MeshZone::slab_only() const
  {
    MeshZone slab = *this;
    for (unsigned int c = 0; c < slab_of.size(); ++c)
      slab.in_zone[c] = (slab_of[c] == rank);
    return slab;
  }

  void
  MeshZone::mark_owners(Triangulation<3> &mesh) const
  {
    for (const auto &cell : mesh.cell_iterators())
      {
        cell->set_level_subdomain_id(owner(cell));
        if (cell->is_active())
          cell->set_subdomain_id(owner(cell));
      }
  }
} // namespace rbc_ifem
