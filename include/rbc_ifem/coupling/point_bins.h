#ifndef rbc_ifem_coupling_point_bins_h
#define rbc_ifem_coupling_point_bins_h

#include <deal.II/base/point.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <unordered_map>
#include <vector>

namespace rbc_ifem
{
  using namespace dealii;

  /**
   * Points sorted into cubic bins of a given edge, to find every pair
   * closer than that edge without looking at all pairs: a pair that close
   * lies in the same or in neighbouring bins. Building costs one pass over
   * the points; a search, the pairs in neighbouring bins.
   */
  class PointBins
  {
  public:
    /// Sort @p points (which must outlive this object) into bins of edge
    /// @p bin_size [µm].
    PointBins(const std::vector<Point<3>> &points, const double bin_size);

    /**
     * Call @p f(i, j) once for every pair i < j of points less than the bin
     * edge apart.
     */
    template <typename Function>
    void
    for_each_close_pair(const Function &f) const
    {
      const double squared_edge = bin_size * bin_size;
      for (unsigned int i = 0; i < points.size(); ++i)
        {
          const std::array<std::int64_t, 3> bin = bin_of(points[i]);
          for (std::int64_t dx = -1; dx <= 1; ++dx)
            for (std::int64_t dy = -1; dy <= 1; ++dy)
              for (std::int64_t dz = -1; dz <= 1; ++dz)
                {
                  const auto found =
                    bins.find(key({{bin[0] + dx, bin[1] + dy, bin[2] + dz}}));
                  if (found == bins.end())
                    continue;
                  for (const unsigned int j : found->second)
                    if (j > i &&
                        points[i].distance_square(points[j]) < squared_edge)
                      f(i, j);
                }
        }
    }

  private:
    std::array<std::int64_t, 3>
    bin_of(const Point<3> &p) const;

    /// One integer for a bin: 21 bits per index, enough for any capillary.
    static std::uint64_t
    key(const std::array<std::int64_t, 3> &bin);

    const std::vector<Point<3>>                                 &points;
    const double                                                 bin_size;
    std::unordered_map<std::uint64_t, std::vector<unsigned int>> bins;
  };
} // namespace rbc_ifem

#endif
