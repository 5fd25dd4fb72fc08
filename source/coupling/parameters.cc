#include <rbc_ifem/base/input_error.h>
#include <rbc_ifem/base/parameter_tools.h>
#include <rbc_ifem/coupling/parameters.h>

#include <algorithm>

namespace rbc_ifem
{
  void
  InteractionParameters::add_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Cell interactions");
    add_parameter(prm,
                  "Repulsion pressure",
                  repulsion_pressure,
                  "p0 of the repulsion between the membranes of different "
                  "cells [pN/µm²]: two membranes a gap h < Repulsion range "
                  "Δ apart push each other apart with the pressure p(h) = "
                  "p0 (Δ/h - 1)², which grows without bound as h -> 0, so "
                  "cells pressed together by the flow do not overlap. "
                  "0: off.",
                  Patterns::Double(0.));
    add_parameter(prm,
                  "Repulsion range",
                  repulsion_range,
                  "Δ of the cell-cell repulsion [µm]: no force beyond it. "
                  "Keep it at least the membrane point spacing (the run "
                  "warns otherwise) and below the cell diameter.",
                  GreaterThan());
    add_parameter(prm,
                  "Aggregation",
                  aggregation,
                  "true adds the attraction of red cell aggregation between "
                  "the membranes of different cells: the Morse potential per "
                  "unit area φ(h) = D_e [e^{2β(r0-h)} - 2 e^{β(r0-h)}] of "
                  "the gap h (Liu & Liu 2006, J. Comput. Phys. 220:139; "
                  "Zhang, Johnson & Popel 2008, J. Biomech. 41:47), zero "
                  "beyond Aggregation cutoff.");
    add_parameter(prm,
                  "Aggregation energy",
                  aggregation_energy,
                  "D_e, the depth of the Morse well [pN/µm, i.e. µJ/m²]. "
                  "0.3 µJ/m² is the weak aggregation of Liu & Liu 2006 and "
                  "of Zhang et al. 2008, who go up to 3 for strong "
                  "rouleaux.",
                  Patterns::Double(0.));
    add_parameter(prm,
                  "Aggregation width",
                  aggregation_width,
                  "β, the inverse width of the Morse well [1/µm] (3.84 in "
                  "Liu & Liu 2006 and Zhang et al. 2008).",
                  GreaterThan());
    add_parameter(prm,
                  "Aggregation distance",
                  aggregation_distance,
                  "r0, the gap of the Morse minimum between two flat "
                  "membranes [µm] (0.49 in Liu & Liu 2006 and Zhang et al. "
                  "2008).",
                  Patterns::Double(0.));
    add_parameter(prm,
                  "Aggregation cutoff",
                  aggregation_cutoff,
                  "The gap beyond which the Morse potential is zero [µm]; "
                  "the potential is shifted so that it and its force are "
                  "continuous there. Must exceed Aggregation distance.",
                  GreaterThan());
    add_parameter(prm,
                  "Wall pressure",
                  wall_pressure,
                  "p0 of the repulsion from the capillary wall [pN/µm²]: a "
                  "membrane a gap d < Wall range Δ from the wall is pushed "
                  "back into the lumen with p(d) = p0 (Δ/d - 1)². 0: off "
                  "(a cell that reaches the wall then stops the run).",
                  Patterns::Double(0.));
    add_parameter(prm,
                  "Wall range",
                  wall_range,
                  "Δ of the wall repulsion [µm]: no force farther from the "
                  "wall. Below the capillary radius.",
                  GreaterThan());
    prm.leave_subsection();
  }

  void
  InteractionParameters::validate(const double cell_diameter,
                                  const double capillary_radius,
                                  const double segment_length) const
  {
    const auto require_shorter = [](const std::string &parameter,
                                    const double       range,
                                    const double       limit,
                                    const std::string &what) {
      if (!(range < limit))
        throw InputError(parameter,
                         to_text(range),
                         "a range below " + what + ", " + to_text(limit) +
                           " µm.");
    };
    const double      cell_limit = std::min(cell_diameter, segment_length / 2.);
    const std::string cell_what  = cell_limit < cell_diameter ?
                                     "half the capillary length" :
                                     "the cell diameter";
    if (repulsion_pressure > 0.)
      require_shorter("Cell interactions/Repulsion range",
                      repulsion_range,
                      cell_limit,
                      cell_what);
    if (aggregation)
      {
        require_shorter("Cell interactions/Aggregation cutoff",
                        aggregation_cutoff,
                        cell_limit,
                        cell_what);
        if (!(aggregation_cutoff > aggregation_distance))
          throw InputError("Cell interactions/Aggregation cutoff",
                           to_text(aggregation_cutoff),
                           "a gap beyond the Morse minimum, Aggregation "
                           "distance = " +
                             to_text(aggregation_distance) + " µm.");
      }
    if (wall_pressure > 0.)
      require_shorter("Cell interactions/Wall range",
                      wall_range,
                      capillary_radius,
                      "the capillary radius");
  }
} // namespace rbc_ifem
