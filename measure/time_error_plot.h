// The comparison's run-time-against-error plot as inline SVG: one point per method id (median frame time on a log
// axis, mean RMSE against the ray-cast truth on a linear one), coloured by family, the Pareto front (the rows
// flagged `pareto`) drawn as a step line with its points ringed, and a <title> on every point for hover labels.
#pragma once

#include <string>
#include <vector>

#include "measure/compare_results.h"

namespace rtm {

struct TimeErrorPlot {
    std::string svg;
    std::vector<std::string> left_out;  // method ids without a finite positive time or a finite RMSE
};

// `rows`: the summary rows of one source (or of "all"). `plot_id` names the <svg> element (unique in the page).
TimeErrorPlot time_error_plot(const std::vector<SummaryRow>& rows, const std::string& plot_id);

// The colour of a family's points and legend entry ("#rrggbb").
std::string family_colour(const std::string& family);

}  // namespace rtm
