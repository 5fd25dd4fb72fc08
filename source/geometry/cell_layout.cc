#include <rbc_ifem/base/input_error.h>
#include <rbc_ifem/geometry/cell_layout.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <sstream>

namespace rbc_ifem
{
  namespace
  {
    std::string
    format(const double value)
    {
      std::ostringstream s;
      s.precision(4);
      s << value;
      return s.str();
    }
  } // namespace

  CellLayout::CellLayout(const LayoutParameters   &layout,
                         const GeometryParameters &geometry,
                         const CellParameters     &cell_parameters)
    : layout(layout)
    , geometry(geometry)
    , axis(cell_parameters.axis)
  {
    if (cell_parameters.diameter >= 2. * geometry.capillary_radius)
      throw InputError("Cells/Diameter",
                       to_text(cell_parameters.diameter),
                       "the cell must be smaller than the capillary diameter "
                       "2 x Geometry/Capillary radius = " +
                         to_text(2. * geometry.capillary_radius) +
                         " µm (a flowing run can squeeze a wider cell in: "
                         "Immersed cells/Squeeze into lumen).");
    const EvansFungShape shape = EvansFungShape::of(cell_parameters);
    const CellPlacement  reference{Point<3>(), axis};
    const Tensor<1, 3>   e_x{{1., 0., 0.}};

    // The shape is centrally symmetric, so its extent along +x and -x agree.
    // It also lies inside the ball of radius R about its centre, so a cell on
    // the axis clears the wall in any orientation once its diameter is
    // smaller than the capillary's (checked above).
    length_of_cell = 2. * shape.extent(reference, e_x);

    if (layout.n_cells > max_cells())
      {
        const std::string what =
          layout.kind == LayoutKind::clustered ?
            "a clustered group of " + std::to_string(layout.n_cells) +
              " cells is " +
              format(layout.n_cells * length_of_cell +
                     (layout.n_cells - 1) * layout.minimum_gap) +
              " µm long, longer than the segment less the end clearances (" +
              format(geometry.capillary_length - layout.minimum_gap) +
              " µm); at most " + std::to_string(max_cells()) + " cells fit." :
            "a segment of Geometry/Capillary length = " +
              format(geometry.capillary_length) + " µm holds at most " +
              std::to_string(max_cells()) + " cells of length " +
              format(length_of_cell) +
              " µm with Layout/Minimum gap = " + format(layout.minimum_gap) +
              " µm.";
        throw InputError("Layout/Number of cells",
                         std::to_string(layout.n_cells),
                         what);
      }

    switch (layout.kind)
      {
        case LayoutKind::uniform:
          place_uniform();
          break;
        case LayoutKind::random:
          place_random();
          break;
        case LayoutKind::clustered:
          place_clustered();
          break;
      }
  }

  const std::vector<CellPlacement> &
  CellLayout::placements() const
  {
    return cells;
  }

  const LayoutParameters &
  CellLayout::parameters() const
  {
    return layout;
  }

  double
  CellLayout::cell_length() const
  {
    return length_of_cell;
  }

  unsigned int
  CellLayout::max_cells() const
  {
    const double pitch = length_of_cell + layout.minimum_gap;
    return static_cast<unsigned int>(
      std::floor(geometry.capillary_length / pitch * (1. + 1e-12)));
  }

  double
  CellLayout::hematocrit(const std::vector<double> &cell_volumes) const
  {
    double total = 0.;
    for (const double v : cell_volumes)
      total += v;
    return total / (numbers::PI * geometry.capillary_radius *
                    geometry.capillary_radius * geometry.capillary_length);
  }

  void
  CellLayout::add_cell_at(const double x)
  {
    cells.push_back(CellPlacement{Point<3>(x, 0., 0.), axis});
  }

  void
  CellLayout::place_uniform()
  {
    const double spacing = geometry.capillary_length / layout.n_cells;
    for (unsigned int i = 0; i < layout.n_cells; ++i)
      add_cell_at((i + 0.5) * spacing);
  }

  void
  CellLayout::place_random()
  {
    // Cell i sits at (i + 1/2) pitch plus the i-th smallest of N uniform
    // draws from [0, slack]: this is the uniform distribution over all
    // ordered arrangements that keep the gaps. The numbers come straight
    // from mt19937, whose output the C++ standard fixes, so a seed gives the
    // same layout with every compiler and on every MPI rank.
    const double pitch = length_of_cell + layout.minimum_gap;
    const double slack = geometry.capillary_length - layout.n_cells * pitch;

    std::mt19937        generator(layout.seed);
    std::vector<double> shifts(layout.n_cells);
    for (double &shift : shifts)
      shift = slack * (generator() / 4294967296.);
    std::sort(shifts.begin(), shifts.end());

    for (unsigned int i = 0; i < layout.n_cells; ++i)
      add_cell_at(shifts[i] + (i + 0.5) * pitch);
  }

  void
  CellLayout::place_clustered()
  {
    const double pitch        = length_of_cell + layout.minimum_gap;
    const double group_length = layout.n_cells * length_of_cell +
                                (layout.n_cells - 1) * layout.minimum_gap;
    const double centre = layout.cluster_position * geometry.capillary_length;

    // The group keeps half a gap from each end face, like every layout.
    const double lowest  = 0.5 * (group_length + layout.minimum_gap);
    const double highest = geometry.capillary_length - lowest;
    if (layout.n_cells > 0 &&
        (centre < lowest - 1e-12 * geometry.capillary_length ||
         centre > highest + 1e-12 * geometry.capillary_length))
      throw InputError("Layout/Cluster position",
                       format(layout.cluster_position),
                       "the group of " + std::to_string(layout.n_cells) +
                         " cells is " + format(group_length) +
                         " µm long; to stay inside the segment its centre "
                         "must lie between " +
                         format(lowest / geometry.capillary_length) + " and " +
                         format(highest / geometry.capillary_length) +
                         " of the capillary length.");

    const double first = centre - 0.5 * group_length + 0.5 * length_of_cell;
    for (unsigned int i = 0; i < layout.n_cells; ++i)
      add_cell_at(first + i * pitch);
  }
} // namespace rbc_ifem
