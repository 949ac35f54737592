/// \file
/// \brief Axes: labels, limits, data series, and the data -> pixel transform.
#include "plot/axes.hpp"

#include "plot/error.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace plot {
namespace {

std::string quote(const std::string& s) { return "'" + s + "'"; }

bool finite(double v) { return std::isfinite(v); }

void require(bool ok, const std::string& message) {
    if (!ok) throw Error(message);
}

}  // namespace

std::string Axes::name() const {
    return letter_.empty() ? "panel " + std::to_string(index_ + 1) : "panel " + letter_;
}

// ---- Labels and limits ------------------------------------------------------------------------
// Markup is parsed once here so that a typo fails where it was written, not at render time.
Axes& Axes::xlabel(std::string markup) {
    parse_markup(markup);
    xlabel_ = std::move(markup);
    return *this;
}

Axes& Axes::ylabel(std::string markup) {
    parse_markup(markup);
    ylabel_ = std::move(markup);
    return *this;
}

Axes& Axes::title(std::string markup) {
    parse_markup(markup);
    title_ = std::move(markup);
    return *this;
}

Axes& Axes::letter(std::string markup) {
    parse_markup(markup);
    letter_ = std::move(markup);
    return *this;
}

Axes& Axes::xlim(double lo, double hi) {
    require(finite(lo) && finite(hi) && lo < hi, name() + ": xlim(" + std::to_string(lo) + ", " +
                                                     std::to_string(hi) + ") needs finite lo < hi");
    xlim_ = {lo, hi};
    return *this;
}

Axes& Axes::ylim(double lo, double hi) {
    require(finite(lo) && finite(hi) && lo < hi, name() + ": ylim(" + std::to_string(lo) + ", " +
                                                     std::to_string(hi) + ") needs finite lo < hi");
    ylim_ = {lo, hi};
    return *this;
}

Axes& Axes::xscale(Scale scale) {
    xscale_ = scale;
    return *this;
}

Axes& Axes::yscale(Scale scale) {
    yscale_ = scale;
    return *this;
}

Axes& Axes::equal_aspect(bool on) {
    equal_aspect_ = on;
    return *this;
}

Axes& Axes::hide(bool hidden) {
    hidden_ = hidden;
    return *this;
}

Axes& Axes::legend(Corner corner, bool make_room) {
    legend_ = corner;
    legend_room_ = make_room;
    return *this;
}

// ---- Data -------------------------------------------------------------------------------------
Color Axes::next_color() { return cycle_color(colors_used_++); }

/// Checks and copies one x-y series; counts its non-finite points.
Axes::Series& Axes::add_series(Kind kind, std::span<const double> x, std::span<const double> y,
                               std::string label, const char* what) {
    std::string id = name();
    id.append(", ").append(what);
    if (!label.empty()) id.append(" ").append(quote(label));
    parse_markup(label);
    require(!x.empty() || !y.empty(), id + ": no data (empty arrays)");
    require(x.size() == y.size(), id + ": x has " + std::to_string(x.size()) +
                                      " values but y has " + std::to_string(y.size()));
    std::size_t bad = 0;
    for (std::size_t i = 0; i < x.size(); ++i) bad += !(finite(x[i]) && finite(y[i]));
    require(bad < x.size(),
            id + ": all " + std::to_string(x.size()) + " points are NaN or infinite");
    skipped_nonfinite_ += bad;

    Series s{kind,  {x.begin(), x.end()}, {y.begin(), y.end()}, {}, {}, {}, {},
             black, std::move(label)};
    series_.push_back(std::move(s));
    return series_.back();
}

Axes& Axes::scatter(std::span<const double> x, std::span<const double> y,
                    const ScatterOptions& options) {
    require(options.size > 0 && options.size <= 80, name() + ": scatter marker size " +
                                                        std::to_string(options.size) +
                                                        " px is outside (0, 80]");
    require(options.alpha > 0 && options.alpha <= 1, name() + ": scatter alpha must lie in (0, 1]");
    Series& s = add_series(Kind::scatter, x, y, options.label, "scatter");
    s.scatter = options;
    s.color = options.color ? *options.color : next_color();
    return *this;
}

Axes& Axes::scatter(std::span<const double> x, std::span<const double> y,
                    std::span<const double> values, const ColorScatterOptions& options) {
    require(values.size() == x.size(), name() + ": coloured scatter has " +
                                           std::to_string(x.size()) + " points but " +
                                           std::to_string(values.size()) + " values");
    require(options.size > 0 && options.size <= 80,
            name() + ": scatter marker size is outside (0, 80]");
    Series& s = add_series(Kind::color_scatter, x, y, options.label, "coloured scatter");
    s.values.assign(values.begin(), values.end());
    s.color_scatter = options;
    parse_markup(options.colorbar_label);
    return *this;
}

Axes& Axes::line(std::span<const double> x, std::span<const double> y, const LineOptions& options) {
    require(options.width > 0 && options.width <= 40,
            name() + ": line width " + std::to_string(options.width) + " px is outside (0, 40]");
    require(options.marker_size > 0 && options.marker_size <= 80,
            name() + ": marker size is outside (0, 80]");
    Series& s = add_series(Kind::line, x, y, options.label, "line");
    s.line = options;
    s.color = options.color ? *options.color : next_color();
    return *this;
}

Axes& Axes::hline(double y, const LineOptions& options) {
    require(finite(y), name() + ": hline at a non-finite value");
    const double v[1] = {y};
    Series& s = add_series(Kind::hline, v, v, options.label, "hline");
    s.line = options;
    s.color = options.color.value_or(grey);
    return *this;
}

Axes& Axes::vline(double x, const LineOptions& options) {
    require(finite(x), name() + ": vline at a non-finite value");
    const double v[1] = {x};
    Series& s = add_series(Kind::vline, v, v, options.label, "vline");
    s.line = options;
    s.color = options.color.value_or(grey);
    return *this;
}

Axes& Axes::image(const Eigen::ArrayXXd& grid, const Extent& extent, const ImageOptions& options) {
    // Eigen stores column-major: grid(i, j) at i + rows * j, i.e. x fastest, as wanted.
    return image(std::span<const double>(grid.data(), static_cast<std::size_t>(grid.size())),
                 static_cast<int>(grid.rows()), static_cast<int>(grid.cols()), extent, options);
}

Axes& Axes::image(std::span<const double> values, int nx, int ny, const Extent& extent,
                  const ImageOptions& options) {
    const std::string id = name() + ", image";
    require(nx > 0 && ny > 0,
            id + ": empty grid (" + std::to_string(nx) + "×" + std::to_string(ny) + ")");
    require(nx <= 16384 && ny <= 16384, id + ": a " + std::to_string(nx) + "×" +
                                            std::to_string(ny) +
                                            " grid exceeds 16384 cells a side");
    require(values.size() == static_cast<std::size_t>(nx) * static_cast<std::size_t>(ny),
            id + ": " + std::to_string(values.size()) + " values for a " + std::to_string(nx) +
                "×" + std::to_string(ny) + " grid");
    require(finite(extent.x0) && finite(extent.x1) && finite(extent.y0) && finite(extent.y1) &&
                extent.x0 < extent.x1 && extent.y0 < extent.y1,
            id + ": the extent needs finite x0 < x1 and y0 < y1");
    const auto bad = static_cast<std::size_t>(
        std::count_if(values.begin(), values.end(), [](double v) { return !finite(v); }));
    require(bad < values.size(),
            id + ": all " + std::to_string(values.size()) + " cells are NaN or infinite");
    parse_markup(options.colorbar_label);
    skipped_nonfinite_ += bad;
    layers_.push_back({{values.begin(), values.end()}, nx, ny, extent, options});
    return *this;
}

Axes& Axes::text(double x, double y, std::string markup, const TextOptions& options) {
    require(finite(x) && finite(y), name() + ": text at a non-finite position");
    parse_markup(markup);
    annotations_.push_back({x, y, std::move(markup), options});
    return *this;
}

// ---- Limits -----------------------------------------------------------------------------------
/// The limits the data asks for: the range of every finite value (positive, on a log axis),
/// padded by 4 % of the range (in log space on a log axis) unless only images set it.
std::pair<double, double> Axes::auto_limits(bool x_axis) const {
    const bool log = (x_axis ? xscale_ : yscale_) == Scale::log;
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    bool padded = false;
    auto take = [&](double v) {
        if (!finite(v) || (log && v <= 0)) return;
        lo = std::min(lo, v);
        hi = std::max(hi, v);
    };
    for (const Series& s : series_) {
        if ((s.kind == Kind::hline && x_axis) || (s.kind == Kind::vline && !x_axis)) continue;
        const std::vector<double>& v = x_axis ? s.x : s.y;
        const std::vector<double>& other = x_axis ? s.y : s.x;
        for (std::size_t i = 0; i < v.size(); ++i)
            if (finite(other[i])) take(v[i]);
        padded = true;
    }
    for (const Layer& layer : layers_) {
        take(x_axis ? layer.extent.x0 : layer.extent.y0);
        take(x_axis ? layer.extent.x1 : layer.extent.y1);
    }
    if (!(lo <= hi)) {
        if (!series_.empty() || !layers_.empty())
            throw Error(name() + ": no " + (log ? "positive " : "finite ") + (x_axis ? "x" : "y") +
                        " values to set the " + (log ? "logarithmic " : "") + "axis limits from");
        return log ? std::pair{1.0, 10.0} : std::pair{0.0, 1.0};
    }
    if (lo == hi) {  // a single value: open a window around it
        if (log) return {lo / 2, hi * 2};
        const double d = lo == 0 ? 1.0 : 0.1 * std::abs(lo);
        return {lo - d, hi + d};
    }
    if (!padded) return {lo, hi};
    if (log) {
        const double f = std::pow(hi / lo, 0.04);
        return {lo / f, hi * f};
    }
    const double d = 0.04 * (hi - lo);
    return {lo - d, hi + d};
}

void Axes::resolve_limits() {
    std::tie(r_.x_lo, r_.x_hi) = xlim_ ? *xlim_ : auto_limits(true);
    std::tie(r_.y_lo, r_.y_hi) = ylim_ ? *ylim_ : auto_limits(false);
    if (xscale_ == Scale::log && r_.x_lo <= 0)
        throw Error(name() + ": the logarithmic x axis needs positive limits, not " +
                    std::to_string(r_.x_lo));
    if (yscale_ == Scale::log && r_.y_lo <= 0)
        throw Error(name() + ": the logarithmic y axis needs positive limits, not " +
                    std::to_string(r_.y_lo));

    // Points a log axis cannot show are skipped and counted (once per render).
    skipped_nonpositive_ = 0;
    for (const Series& s : series_) {
        for (std::size_t i = 0; i < s.x.size(); ++i) {
            if (!(finite(s.x[i]) && finite(s.y[i]))) continue;
            const bool bad_x = xscale_ == Scale::log && s.kind != Kind::hline && s.x[i] <= 0;
            const bool bad_y = yscale_ == Scale::log && s.kind != Kind::vline && s.y[i] <= 0;
            skipped_nonpositive_ += bad_x || bad_y;
        }
    }
}

// ---- Colour scales ------------------------------------------------------------------------------
Color Axes::ColorRange::at(double value) const {
    const double t = log ? (std::log10(value) - std::log10(lo)) / (std::log10(hi) - std::log10(lo))
                         : (value - lo) / (hi - lo);
    return map_color(map, t);
}

Axes::ColorRange Axes::resolve_color_range(Colormap map, std::optional<double> zmin,
                                           std::optional<double> zmax, bool log,
                                           const std::string& label,
                                           std::span<const double> values) const {
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (double v : values) {
        if (!finite(v) || (log && v <= 0)) continue;
        lo = std::min(lo, v);
        hi = std::max(hi, v);
    }
    lo = zmin.value_or(lo);
    hi = zmax.value_or(hi);
    if (!(lo <= hi) || !finite(lo) || !finite(hi))
        throw Error(name() + ": no " + std::string(log ? "positive " : "finite ") +
                    "values for the colour scale");
    if (log && lo <= 0) throw Error(name() + ": a logarithmic colour scale needs zmin > 0");
    if (lo == hi) {
        if (log) {
            lo /= 2;
            hi *= 2;
        } else {
            const double d = lo == 0 ? 1.0 : 0.1 * std::abs(lo);
            lo -= d;
            hi += d;
        }
    }
    return {map, lo, hi, log, label};
}

// ---- Transform and queries --------------------------------------------------------------------
double Axes::axis_u(double v, bool x_axis) const {
    return (x_axis ? xscale_ : yscale_) == Scale::log ? std::log10(v) : v;
}

Point Axes::to_pixel(double x, double y) const {
    require_rendered();
    const double ux =
        (axis_u(x, true) - axis_u(r_.x_lo, true)) / (axis_u(r_.x_hi, true) - axis_u(r_.x_lo, true));
    const double uy = (axis_u(y, false) - axis_u(r_.y_lo, false)) /
                      (axis_u(r_.y_hi, false) - axis_u(r_.y_lo, false));
    return {r_.frame.x0 + ux * r_.frame.width(), r_.frame.y1 - uy * r_.frame.height()};
}

void Axes::require_rendered() const {
    if (!r_.done) throw Error(name() + ": the figure has not been rendered yet");
}

Rect Axes::legend_box() const {
    require_rendered();
    return r_.legend_entries.empty() ? Rect{} : r_.legend_box;
}

Rect Axes::frame() const {
    require_rendered();
    return r_.frame;
}

std::pair<double, double> Axes::xrange() const {
    require_rendered();
    return {r_.x_lo, r_.x_hi};
}

std::pair<double, double> Axes::yrange() const {
    require_rendered();
    return {r_.y_lo, r_.y_hi};
}

const TickSet& Axes::xticks() const {
    require_rendered();
    return r_.x_ticks;
}

const TickSet& Axes::yticks() const {
    require_rendered();
    return r_.y_ticks;
}

}  // namespace plot
