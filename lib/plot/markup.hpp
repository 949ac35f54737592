/// \file
/// \brief A small TeX-like markup for labels: Greek letters, symbols, sub- and superscripts.
///
/// The markup is what one would type between dollar signs in a paper, kept small:
///
/// | input                         | shows                     |
/// |-------------------------------|---------------------------|
/// | `\rho`, `\Delta`, `\nabla`    | ρ, Δ, ∇ (all Greek letters, upper and lower case) |
/// | `v_x`, `t_{run}`              | v with subscript x, t with subscript "run" |
/// | `t_{run}^{-1}`, `v_x^2`       | a sub- and a superscript stacked over each other |
/// | `10^{-3}`, `r^2`              | superscripts; braces group, nest: `e^{x^{2}}` |
/// | `\times \cdot \pm \le \ge \propto \approx \sim` | binary operators and relations, set with thin spaces around them as TeX does |
/// | `\infty \partial \langle \rangle \odot \prime \ell \degree` | symbols |
/// | `\mathrm{run}`, `\text{run}`  | the group's text unchanged (accepted so TeX habits work) |
/// | `\,` `\ ` `\{` `\}` `\\` `\_` `\^` | thin space, space, literal characters |
///
/// Spaces are kept as typed (labels are mostly words), except next to a binary operator or
/// relation.  A hyphen directly before a digit, at the start of the label, a group, or after a
/// space, '(' or '=', becomes a proper minus sign (U+2212).  An unknown command, a stray `}`
/// or an unclosed `{` throws plot::Error naming it.
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace plot {

/// A stretch of text set at one size and one baseline.
struct TextRun {
    std::string text;    ///< UTF-8
    double shift = 0.0;  ///< baseline shift in units of the base font size, positive upwards
    double scale = 1.0;  ///< font size relative to the base font size
    /// Set on a script that directly follows a script of the other kind (`v_x^2`): it starts
    /// where the previous run started, so the two stack as in TeX.
    bool stacked = false;
    friend bool operator==(const TextRun&, const TextRun&) = default;
};

/// Parses \p markup into runs; neighbouring runs with equal shift and scale are merged.
/// Throws plot::Error on an unknown command or unbalanced braces.
std::vector<TextRun> parse_markup(std::string_view markup);

/// The plain text of a run list (all runs concatenated), handy in tests and messages.
std::string plain_text(const std::vector<TextRun>& runs);

}  // namespace plot
