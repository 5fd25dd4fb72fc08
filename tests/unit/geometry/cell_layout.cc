// Cell layouts: for every kind, every feasible number of cells and random
// seeds 1..20 no two membrane meshes come closer than Minimum gap and none
// touches the wall (measured between the meshed surfaces, not the centres);
// uniform spacing and clustered gaps are exact; random layouts are
// reproducible; the hematocrit is total cell volume / lumen volume. A
// layout written as a file (Layout/Kind = file) reads back as the same
// cells, and a file whose cells overlap, come too close, leave the segment
// or the lumen, or that is malformed, is refused with the file, the line
// and the cell named.

#include <rbc_ifem/base/input_error.h>
#include <rbc_ifem/geometry/cell_layout.h>
#include <rbc_ifem/geometry/cell_surface.h>

#include "check.h"

#include <cstdio>
#include <fstream>
#include <memory>

using namespace rbc_ifem;

namespace
{
  /// Build the membranes of a layout and measure their clearance.
  Clearance
  clearance_of(const CellLayout         &layout,
               const CellParameters     &cells,
               const GeometryParameters &geometry,
               const unsigned int        refinements)
  {
    const EvansFungShape                              shape(cells.diameter);
    std::vector<std::unique_ptr<Triangulation<2, 3>>> surfaces;
    std::vector<const Triangulation<2, 3> *>          pointers;
    for (const CellPlacement &placement : layout.placements())
      {
        surfaces.push_back(std::make_unique<Triangulation<2, 3>>());
        create_cell_surface(*surfaces.back(), shape, placement, refinements);
        pointers.push_back(surfaces.back().get());
      }
    return measure_clearance(pointers,
                             MappingQ<2, 3>(2),
                             geometry.capillary_radius);
  }

  /// The largest |x_i - expected(i)| over the cells' centres.
  template <typename Expected>
  double
  largest_deviation(const CellLayout &layout, const Expected &expected)
  {
    double worst = 0.;
    for (unsigned int i = 0; i < layout.placements().size(); ++i)
      worst =
        std::max(worst,
                 std::abs(layout.placements()[i].center[0] - expected(i)));
    return worst;
  }

  /// The largest half thickness of the profile, by dense sampling.
  double
  sampled_half_length(const double R)
  {
    const EvansFungShape shape(2. * R);
    double               best = 0.;
    for (unsigned int i = 0; i <= 200000; ++i)
      best = std::max(best, shape.half_thickness(R * i / 200000.));
    return best;
  }
} // namespace

int
main()
{
  Checker                  check;
  const GeometryParameters geometry;
  const CellParameters     cells;
  LayoutParameters         layout;
  const double             gap = layout.minimum_gap;

  // The cell length along the axis is twice the profile's largest half
  // thickness; with it, floor(L / (length + gap)) cells fit: 7, as in the
  // paper.
  const CellLayout reference(layout, geometry, cells);
  check.near("cell length along the axis [µm]",
             reference.cell_length(),
             2. * sampled_half_length(cells.diameter / 2.),
             1e-8);
  check.near("cells that fit in 20 µm", reference.max_cells(), 7., 0.);

  // Every kind, every feasible N, seeds 1..20 for random: the meshed
  // surfaces keep the gap (up to the mesh's distance from the true shape,
  // < 1e-3 µm at 2 refinements) and stay off the wall.
  for (const auto &[kind, kind_name] : layout_kind_names())
    {
      if (kind == LayoutKind::file)
        continue; // the round trip below
      layout.kind             = kind;
      double       worst_gap  = std::numeric_limits<double>::infinity();
      double       worst_wall = std::numeric_limits<double>::infinity();
      unsigned int n_runs     = 0;
      for (unsigned int n = 1; n <= reference.max_cells(); ++n)
        for (unsigned int seed = 1;
             seed <= (kind == LayoutKind::random ? 20u : 1u);
             ++seed)
          {
            layout.n_cells = n;
            layout.seed    = seed;
            const CellLayout cell_layout(layout, geometry, cells);
            const Clearance  c = clearance_of(cell_layout, cells, geometry, 2);
            worst_gap          = std::min(worst_gap, c.min_cell_gap);
            worst_wall         = std::min(worst_wall, c.min_wall_gap);
            ++n_runs;
            for (const CellPlacement &p : cell_layout.placements())
              if (p.center[0] - 0.5 * cell_layout.cell_length() <
                    0.5 * gap - 1e-12 ||
                  p.center[0] + 0.5 * cell_layout.cell_length() >
                    geometry.capillary_length - 0.5 * gap + 1e-12)
                check.holds(kind_name + ": a cell leaves the segment", false);
          }
      std::cout << kind_name << ": " << n_runs << " layouts\n";
      check.at_least(kind_name +
                       ": smallest membrane gap over all layouts [µm]",
                     worst_gap,
                     gap - 1e-3);
      check.near(kind_name + ": smallest wall clearance [µm]",
                 worst_wall,
                 geometry.capillary_radius - cells.diameter / 2.,
                 1e-3);
    }

  // Uniform: centres at (i + 1/2) L / N exactly.
  layout.kind    = LayoutKind::uniform;
  layout.n_cells = 6;
  {
    const CellLayout uniform(layout, geometry, cells);
    const double worst = largest_deviation(uniform, [](const unsigned int i) {
      return (i + 0.5) * 20. / 6.;
    });
    check.at_most("uniform: largest deviation from (i+1/2) L/N [µm]",
                  worst,
                  1e-12);
  }

  // Clustered: centres one cell length + gap apart, and the measured gap
  // between neighbouring membranes equal to Minimum gap (the sampled
  // distance overestimates it by < 1e-3 µm at 4 refinements).
  layout.kind    = LayoutKind::clustered;
  layout.n_cells = 5;
  {
    const CellLayout clustered(layout, geometry, cells);
    const double     first = clustered.placements()[0].center[0];
    const double     worst =
      largest_deviation(clustered, [&](const unsigned int i) {
        return first + i * (clustered.cell_length() + gap);
      });
    check.at_most("clustered: centres - (first + i (length + gap)) [µm]",
                  worst,
                  1e-12);
    const double middle = 0.5 * (clustered.placements()[0].center[0] +
                                 clustered.placements()[4].center[0]);
    check.near("clustered: group centre [µm]", middle, 10., 1e-12);
    check.near("clustered: measured gap between membranes [µm]",
               clearance_of(clustered, cells, geometry, 4).min_cell_gap,
               gap,
               1e-3);
  }

  // Random: the same seed gives the same layout, another seed another one.
  layout.kind    = LayoutKind::random;
  layout.n_cells = 4;
  {
    layout.seed = 7;
    const CellLayout a(layout, geometry, cells), b(layout, geometry, cells);
    layout.seed = 8;
    const CellLayout c(layout, geometry, cells);
    bool             same = true, different = false;
    for (unsigned int i = 0; i < 4; ++i)
      {
        same = same && a.placements()[i].center == b.placements()[i].center;
        different =
          different || a.placements()[i].center != c.placements()[i].center;
      }
    check.holds("random: seed 7 twice gives the same layout", same);
    check.holds("random: seeds 7 and 8 give different layouts", different);
  }

  // Kind = file: a random layout written as Layout/File reads back as the
  // same cells (to the ten digits of the file).
  {
    layout.kind    = LayoutKind::random;
    layout.n_cells = 5;
    layout.seed    = 3;
    const CellLayout  drawn(layout, geometry, cells);
    const std::string path = "cell_layout_test_" + drawn.file_name();
    drawn.table().write(path);
    LayoutParameters from_file = layout;
    from_file.kind             = LayoutKind::file;
    from_file.file             = path;
    const CellLayout read(from_file, geometry, cells);
    double           worst = 0.;
    for (unsigned int i = 0; i < 5; ++i)
      worst = std::max(
        {worst,
         read.placements()[i].center.distance(drawn.placements()[i].center),
         (read.placements()[i].axis - drawn.placements()[i].axis).norm()});
    check.holds("file: as many cells as written",
                read.placements().size() == 5);
    check.at_most("file: largest change of a centre or axis", worst, 1e-8);
    std::remove(path.c_str());
  }

  // Bad files: each refused, the message naming the file, the line and the
  // cell. The cells are 2.4594 µm long along their axis x: centres
  // 2.5594 µm apart leave a 0.1 µm gap, less than Minimum gap.
  {
    const std::string path    = "cell_layout_test_bad.csv";
    const auto        refused = [&](const std::string &what,
                             const std::string &text,
                             const std::string &expected) {
      std::ofstream(path) << text;
      LayoutParameters l = layout;
      l.kind             = LayoutKind::file;
      l.file             = path;
      try
        {
          CellLayout(l, geometry, cells);
          check.holds("file, " + what + ": refused", false);
        }
      catch (const InputError &e)
        {
          const std::string message = e.what();
          std::cout << "  " << message << '\n';
          check.holds("file, " + what + ": refused, naming the file and '" +
                        expected + "'",
                      message.find(path) != std::string::npos &&
                        message.find(expected) != std::string::npos);
        }
    };
    const std::string header = "x,y,z,axis_x,axis_y,axis_z\n";
    refused("overlapping cells",
            header + "5,0,0,1,0,0\n6,0,0,0,1,1\n",
            "cell 0 (line 2) and cell 1 (line 3) overlap");
    refused("cells 0.1 µm apart",
            header + "5,0,0,1,0,0\n8,0,0,1,0,0\n\n10.5594,0,0,1,0,0\n",
            "cell 1 (line 3) and cell 2 (line 5) are 0.1");
    refused("a cell across an end face",
            header + "1,0,0,1,0,0\n",
            "cell 0 (line 2) spans x = -0.2297");
    refused("a cell outside the lumen",
            header + "10,0,1.5,1,0,0\n",
            "cell 0 (line 2) reaches 5.25");
    refused("a word for a number",
            header + "10,0,0,1,0,0\n14,zero,0,1,0,0\n",
            "line 3 (cell 1): 'zero' is not a number");
    refused("five values", header + "10,0,0,1,0\n", "it has 5 values");
    refused("a zero axis", header + "10,0,0,0,0,0\n", "is not a direction");
    refused("no header", "10,0,0,1,0,0\n", "line 1 must be the header");
    refused("no cells", header, "it has no cells");
    std::remove(path.c_str());
    try
      {
        LayoutParameters l = layout;
        l.kind             = LayoutKind::file;
        l.file             = "no_such_layout.csv";
        CellLayout(l, geometry, cells);
        check.holds("a missing file is refused", false);
      }
    catch (const InputError &e)
      {
        check.holds(std::string("a missing file is refused: ") + e.what(),
                    std::string(e.what()).find("no_such_layout.csv") !=
                      std::string::npos);
      }
  }

  // The exact shape's inside: the centre, not a point beyond the rim.
  {
    const EvansFungShape shape(cells.diameter);
    const CellPlacement  placed{Point<3>(5., 1., 0.),
                               Tensor<1, 3>({0., 0., 2.})};
    check.holds("contains(): the centre is inside",
                shape.contains(placed, Point<3>(5., 1., 0.)));
    check.holds("contains(): the rim region at 0.99 R is inside",
                shape.contains(placed, Point<3>(5. + 0.99 * 3.75, 1., 0.)));
    check.holds("contains(): 1.01 R is outside",
                !shape.contains(placed, Point<3>(5. + 1.01 * 3.75, 1., 0.)));
    check.holds("contains(): the dimple's axis at z = 0.5 µm is outside",
                !shape.contains(placed, Point<3>(5., 1., 0.5)));
    check.near("farthest_from_axis() of a cell standing across the axis",
               shape.farthest_from_axis(placed),
               1. + 3.75,
               1e-8);
  }

  // Tilted cells (axis along z, in the cross-section): the cell length is
  // the diameter, and they still keep the gap.
  {
    CellParameters tilted = cells;
    tilted.axis           = Tensor<1, 3>({0., 0., 1.});
    layout.kind           = LayoutKind::clustered;
    layout.n_cells        = 2;
    const CellLayout standing(layout, geometry, tilted);
    check.near("axis along z: cell length = diameter [µm]",
               standing.cell_length(),
               7.5,
               1e-9);
    check.at_least("axis along z: measured membrane gap [µm]",
                   clearance_of(standing, tilted, geometry, 3).min_cell_gap,
                   gap - 1e-3);
  }

  // Hematocrit = Σ V / (π R² L), here with 7 cells of the exact volume.
  {
    layout.kind    = LayoutKind::uniform;
    layout.n_cells = 7;
    const CellLayout full(layout, geometry, cells);
    const double     v = 82.95803163; // exact, test evans_fung_surface
    check.near("hematocrit of 7 cells",
               full.hematocrit(std::vector<double>(7, v)),
               7. * v / (numbers::PI * 25. * 20.),
               1e-14);
  }

  // Too many cells, and a cluster that does not fit where it is put.
  const auto throws = [&](const std::string &what, const LayoutParameters &l) {
    try
      {
        CellLayout(l, geometry, cells);
        check.holds(what + " is refused", false);
      }
    catch (const InputError &e)
      {
        check.holds(what + " is refused: " + e.what(), true);
      }
  };
  layout.n_cells = 8;
  for (const auto &[kind, kind_name] : layout_kind_names())
    if (kind != LayoutKind::file)
      {
        layout.kind = kind;
        throws("8 cells, " + kind_name, layout);
      }
  layout.n_cells          = 5;
  layout.cluster_position = 0.1;
  throws("a cluster of 5 centred at 0.1 L", layout);

  return check.exit_code();
}
