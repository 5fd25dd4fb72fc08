#include <rbc_ifem/coupling/point_bins.h>

namespace rbc_ifem
{
  PointBins::PointBins(const std::vector<Point<3>> &points,
                       const double                 bin_size)
    : points(points)
    , bin_size(bin_size)
  {
    for (unsigned int i = 0; i < points.size(); ++i)
      bins[key(bin_of(points[i]))].push_back(i);
  }

  std::array<std::int64_t, 3>
  PointBins::bin_of(const Point<3> &p) const
  {
    std::array<std::int64_t, 3> bin;
    for (unsigned int d = 0; d < 3; ++d)
      bin[d] = static_cast<std::int64_t>(std::floor(p[d] / bin_size));
    return bin;
  }

  std::uint64_t
  PointBins::key(const std::array<std::int64_t, 3> &bin)
  {
    constexpr std::int64_t  offset = std::int64_t(1) << 20;
    constexpr std::uint64_t mask   = (std::uint64_t(1) << 21) - 1;
    std::uint64_t           result = 0;
    for (const std::int64_t index : bin)
      result =
        (result << 21) | (static_cast<std::uint64_t>(index + offset) & mask);
    return result;
  }
} // namespace rbc_ifem
