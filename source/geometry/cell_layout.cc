#include <rbc_ifem/base/input_error.h>
#include <rbc_ifem/geometry/cell_layout.h>

#include <deal.II/numerics/rtree.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
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

    /// The columns of a layout file, in order.
    constexpr const char *layout_file_header = "x,y,z,axis_x,axis_y,axis_z";

    /// @p text without blanks (and a CR of a file written on Windows).
    std::string
    without_blanks(const std::string &text)
    {
      std::string out;
      for (const char c : text)
        if (c != ' ' && c != '\t' && c != '\r')
          out += c;
      return out;
    }

    /**
     * Points on the surface of the cell @p placement, the image of a
     * 64 x 128 grid of sphere angles: about 0.2 µm apart on the rim of a
     * 7.5 µm cell, so that the sampled distance between two surfaces
     * exceeds the true one by (spacing)² / (8 radius of curvature) < 0.01 µm.
     */
    std::vector<Point<3>>
    surface_samples(const EvansFungShape &shape, const CellPlacement &placement)
    {
      const unsigned int    n_theta = 64, n_phi = 128;
      const Tensor<2, 3>    q = placement.rotation();
      std::vector<Point<3>> samples;
      for (unsigned int i = 0; i <= n_theta; ++i)
        for (unsigned int j = 0; j < n_phi; ++j)
          {
            const double theta = numbers::PI * i / n_theta,
                         phi   = 2. * numbers::PI * j / n_phi;
            const Point<3> s(std::sin(theta) * std::cos(phi),
                             std::sin(theta) * std::sin(phi),
                             std::cos(theta));
            samples.push_back(placement.center + q * shape.from_sphere(s));
          }
      return samples;
    }

    /**
     * "" if cells @p a and @p b of @p shape keep @p gap between them, else
     * " overlap" or " are D µm apart": the distance between dense samples
     * of their exact surfaces (@p a_samples, also as the r-tree @p a_tree,
     * and @p b_samples), an overlap if a sample of one lies inside the
     * other.
     */
    template <typename Tree>
    std::string
    cells_apart(const EvansFungShape        &shape,
                const double                 gap,
                const CellPlacement         &a,
                const Tree                  &a_tree,
                const std::vector<Point<3>> &a_samples,
                const CellPlacement         &b,
                const std::vector<Point<3>> &b_samples)
    {
      namespace bgi = boost::geometry::index;
      // Cells lie inside the ball of radius R about their centre.
      if (a.center.distance(b.center) >= 2. * shape.radius() + gap)
        return "";
      double closest = std::numeric_limits<double>::infinity();
      bool   overlap = false;
      for (const Point<3> &x : b_samples)
        {
          for (const Point<3> &nearest :
               a_tree | bgi::adaptors::queried(bgi::nearest(x, 1)))
            closest = std::min(closest, x.distance(nearest));
          overlap = overlap || shape.contains(a, x);
        }
      for (const Point<3> &x : a_samples)
        overlap = overlap || shape.contains(b, x);
      if (overlap)
        return " overlap";
      if (closest < gap)
        return " are " + format(closest) + " µm apart";
      return "";
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

    if (layout.kind == LayoutKind::file)
      {
        place_from_file(shape);
        return;
      }
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
        case LayoutKind::file:
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

  std::string
  CellLayout::description() const
  {
    if (layout.kind == LayoutKind::file)
      return "file " + layout.file + ", " + std::to_string(cells.size()) +
             " cells";
    return name_of(layout.kind, layout_kind_names()) + ", " +
           std::to_string(layout.n_cells) + " cells, seed " +
           std::to_string(layout.seed);
  }

  std::string
  CellLayout::file_name() const
  {
    return "layout_" + name_of(layout.kind, layout_kind_names()) + "_" +
           std::to_string(cells.size()) + "_" + std::to_string(layout.seed) +
           ".csv";
  }

  CsvTable
  CellLayout::table() const
  {
    CsvTable table(layout_file_header);
    for (const CellPlacement &cell : cells)
      table.add(cell.center[0],
                cell.center[1],
                cell.center[2],
                cell.axis[0],
                cell.axis[1],
                cell.axis[2]);
    return table;
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

  void
  CellLayout::place_from_file(const EvansFungShape &shape)
  {
    const std::string &path = layout.file;
    const auto         fail = [&](const std::string &why) {
      throw InputError("Layout/File", path, why);
    };
    std::ifstream in(path);
    if (!in)
      fail("the file does not exist or cannot be read.");
    std::string line;
    if (!std::getline(in, line) || without_blanks(line) != layout_file_header)
      fail(std::string("line 1 must be the header ") + layout_file_header +
           ".");
    std::vector<unsigned int> lines;
    for (unsigned int number = 2; std::getline(in, line); ++number)
      {
        if (without_blanks(line).empty())
          continue;
        const std::string where = "line " + std::to_string(number) + " (cell " +
                                  std::to_string(cells.size()) + "): ";
        std::vector<double> values;
        std::istringstream  fields(line);
        for (std::string field; std::getline(fields, field, ',');)
          {
            const std::string text = without_blanks(field);
            std::size_t       used = 0;
            try
              {
                values.push_back(std::stod(text, &used));
              }
            catch (const std::exception &)
              {}
            if (text.empty() || used != text.size() ||
                !std::isfinite(values.back()))
              fail(where + "'" + field + "' is not a number.");
          }
        if (values.size() != 6)
          fail(where + "it has " + std::to_string(values.size()) +
               " values; a row holds 6: " + layout_file_header + ".");
        CellPlacement cell{Point<3>(values[0], values[1], values[2]),
                           Tensor<1, 3>({values[3], values[4], values[5]})};
        if (!(cell.axis.norm() > 0.))
          fail(where + "the axis (0, 0, 0) is not a direction.");
        cells.push_back(cell);
        lines.push_back(number);
      }
    if (cells.empty())
      fail("it has no cells: add a row x,y,z,axis_x,axis_y,axis_z per cell.");
    check_file_cells(shape, lines);
  }

  void
  CellLayout::check_file_cells(const EvansFungShape            &shape,
                               const std::vector<unsigned int> &lines) const
  {
    const auto cell_text = [&](const unsigned int c) {
      return "cell " + std::to_string(c) + " (line " +
             std::to_string(lines[c]) + ")";
    };
    for (unsigned int c = 0; c < cells.size(); ++c)
      check_file_cell_in_segment(shape, cell_text(c), cells[c]);

    std::vector<std::vector<Point<3>>> samples;
    for (const CellPlacement &cell : cells)
      samples.push_back(surface_samples(shape, cell));
    const double period = geometry.periodic ? geometry.capillary_length : 0.;
    for (unsigned int i = 0; i < cells.size(); ++i)
      {
        const auto tree = pack_rtree(samples[i]);
        for (unsigned int j = i + 1; j < cells.size(); ++j)
          {
            // In a periodic segment, cell j's image nearest to cell i.
            const double shift =
              period > 0. ?
                period * std::round((cells[i].center[0] - cells[j].center[0]) /
                                    period) :
                0.;
            CellPlacement image = cells[j];
            image.center[0] += shift;
            std::vector<Point<3>> image_samples = samples[j];
            for (Point<3> &x : image_samples)
              x[0] += shift;
            const std::string apart = cells_apart(shape,
                                                  layout.minimum_gap,
                                                  cells[i],
                                                  tree,
                                                  samples[i],
                                                  image,
                                                  image_samples);
            if (!apart.empty())
              throw InputError("Layout/File",
                               layout.file,
                               cell_text(i) + " and " + cell_text(j) + apart +
                                 (shift != 0. ? " across the periodic end" :
                                                "") +
                                 "; cells keep Layout/Minimum gap = " +
                                 format(layout.minimum_gap) +
                                 " µm between them.");
          }
      }
  }

  void
  CellLayout::check_file_cell_in_segment(const EvansFungShape &shape,
                                         const std::string    &cell_text,
                                         const CellPlacement  &cell) const
  {
    const double gap    = layout.minimum_gap;
    const double length = geometry.capillary_length;
    const auto   fail   = [&](const std::string &why) {
      throw InputError("Layout/File", layout.file, cell_text + why);
    };
    const double reach = shape.extent(cell, Tensor<1, 3>({1., 0., 0.}));
    const double from = cell.center[0] - reach, to = cell.center[0] + reach;
    if (geometry.periodic)
      {
        // A cell may reach across an end: it lies on both sides of it.
        if (cell.center[0] < 0. || cell.center[0] >= length)
          fail(" has its centre at x = " + format(cell.center[0]) +
               " µm; in the periodic segment (Geometry/Periodic) a centre "
               "lies in 0 <= x < Geometry/Capillary length = " +
               format(length) + " µm.");
        if (to - from + gap > length)
          fail(" spans " + format(to - from) +
               " µm along x; with Layout/Minimum gap = " + format(gap) +
               " µm to its own image it must be shorter than the periodic "
               "segment, " +
               format(length) + " µm.");
      }
    else if (from < 0.5 * gap - 1e-12 * length ||
             to > length - 0.5 * gap + 1e-12 * length)
      fail(" spans x = " + format(from) + " to " + format(to) +
           " µm; cells keep half of Layout/Minimum gap = " + format(gap) +
           " µm from the end faces x = 0 and x = " + format(length) +
           " µm (Geometry/Periodic = true lets them cross the ends).");
    const double radius = shape.farthest_from_axis(cell);
    if (radius >= geometry.capillary_radius)
      fail(" reaches " + format(radius) +
           " µm from the axis, outside the lumen of Geometry/Capillary "
           "radius = " +
           format(geometry.capillary_radius) + " µm.");
  }

  CellLayout
  study_layout(const LayoutParameters   &layout,
               const GeometryParameters &geometry,
               const CellParameters     &cells)
  {
    try
      {
        return CellLayout(layout, geometry, cells);
      }
    catch (const InputError &e)
      {
        throw InputError("Layout study/Numbers of cells",
                         std::to_string(layout.n_cells),
                         "the " + name_of(layout.kind, layout_kind_names()) +
                           " layout of that many cells is impossible: " +
                           e.what());
      }
  }
} // namespace rbc_ifem
