// The label markup: Greek letters, symbols, scripts, groups, and clear errors.
#include "plot/error.hpp"
#include "plot/markup.hpp"

#include <catch2/catch.hpp>

using plot::parse_markup;
using plot::plain_text;
using plot::TextRun;

TEST_CASE("markup: plain text is one run at the base size", "[plot][markup]") {
    const auto runs = parse_markup("x [length]");
    REQUIRE(runs.size() == 1);
    CHECK(runs[0] == TextRun{"x [length]", 0.0, 1.0});
    CHECK(parse_markup("").empty());
}

TEST_CASE("markup: Greek letters and symbols", "[plot][markup]") {
    const std::pair<const char*, const char*> cases[] = {
        {"\\rho", "ρ"},        {"\\alpha", "α"}, {"\\beta", "β"},   {"\\gamma", "γ"},
        {"\\mu", "μ"},         {"\\nu", "ν"},    {"\\sigma", "σ"},  {"\\pi", "π"},
        {"\\eta", "η"},        {"\\nabla", "∇"}, {"\\langle", "⟨"}, {"\\rangle", "⟩"},
        {"\\Delta", "Δ"},      {"\\Pi", "Π"},    {"\\Sigma", "Σ"},  {"\\epsilon", "ϵ"},
        {"\\varepsilon", "ε"}, {"\\omega", "ω"}, {"\\infty", "∞"},  {"\\partial", "∂"},
    };
    for (const auto& [input, expected] : cases) {
        INFO(input);
        CHECK(plain_text(parse_markup(input)) == expected);
    }
}

TEST_CASE("markup: operators and relations get TeX-like thin spaces", "[plot][markup]") {
    // U+2005 (1/4 em) around binary operators, U+2004 (1/3 em) around relations.
    CHECK(plain_text(parse_markup("\\nabla\\times\\nabla\\times v")) ==
          "∇\u2005×\u2005∇\u2005×\u2005v");
    CHECK(plain_text(parse_markup("a \\cdot b")) == "a\u2005⋅\u2005b");
    CHECK(plain_text(parse_markup("x \\le 1")) == "x\u2004≤\u20041");
    CHECK(plain_text(parse_markup("x\\ge1")) == "x\u2004≥\u20041");
    CHECK(plain_text(parse_markup("\\propto t")) == "∝\u2004t");  // nothing to the left
    CHECK(plain_text(parse_markup("\\pm 0.1")) == "±0.1");        // unary
    CHECK(plain_text(parse_markup("1 \\pm 0.1")) == "1\u2005±\u20050.1");
}

TEST_CASE("markup: spaces after letters are kept as typed", "[plot][markup]") {
    CHECK(plain_text(parse_markup("\\rho [kg m^{-3}]")) == "ρ [kg m−3]");
}

TEST_CASE("markup: superscripts and subscripts", "[plot][markup]") {
    SECTION("braced superscript, with a real minus sign") {
        const auto runs = parse_markup("10^{-3}");
        REQUIRE(runs.size() == 2);
        CHECK(runs[0] == TextRun{"10", 0.0, 1.0});
        CHECK(runs[1].text == "−3");
        CHECK(runs[1].shift > 0.3);
        CHECK(runs[1].scale == Approx(0.7));
    }
    SECTION("single-character subscript") {
        const auto runs = parse_markup("v_x");
        REQUIRE(runs.size() == 2);
        CHECK(runs[0].text == "v");
        CHECK(runs[1].text == "x");
        CHECK(runs[1].shift < 0.0);
        CHECK(runs[1].scale == Approx(0.7));
    }
    SECTION("text after a script returns to the baseline") {
        const auto runs = parse_markup("t_{run} [s]");
        REQUIRE(runs.size() == 3);
        CHECK(runs[1].text == "run");
        CHECK(runs[2] == TextRun{" [s]", 0.0, 1.0});
    }
    SECTION("a command as a script") {
        const auto runs = parse_markup("M_\\odot");
        REQUIRE(runs.size() == 2);
        CHECK(runs[1].text == "⊙");
    }
    SECTION("nested scripts shrink and rise further") {
        const auto runs = parse_markup("e^{x^{2}}");
        REQUIRE(runs.size() == 3);
        CHECK(runs[2].text == "2");
        CHECK(runs[2].scale == Approx(0.49));
        CHECK(runs[2].shift > runs[1].shift);
    }
    SECTION("a UTF-8 character as a script argument stays whole") {
        const auto runs = parse_markup("x_ρ");
        REQUIRE(runs.size() == 2);
        CHECK(runs[1].text == "ρ");
    }
}

TEST_CASE("markup: groups, escapes and TeX habits", "[plot][markup]") {
    CHECK(plain_text(parse_markup("{a{b}c}")) == "abc");
    CHECK(plain_text(parse_markup("t_{\\mathrm{run}}")) == "trun");
    CHECK(plain_text(parse_markup("\\{x\\} 50\\% a\\_b")) == "{x} 50% a_b");
    CHECK(plain_text(parse_markup("a\\,b")) == "a\u2006b");
    CHECK(plain_text(parse_markup("x-axis")) == "x-axis");  // a hyphen stays a hyphen
    CHECK(plain_text(parse_markup("-0.5")) == "−0.5");      // a number's sign becomes a minus
    CHECK(plain_text(parse_markup("x = -1")) == "x = −1");
}

TEST_CASE("markup: errors name the problem", "[plot][markup][errors]") {
    CHECK_THROWS_AS(parse_markup("\\foo"), plot::Error);
    CHECK_THROWS_WITH(parse_markup("\\rhoo + 1"), Catch::Contains("unknown command \\rhoo"));
    CHECK_THROWS_WITH(parse_markup("10^{-3"), Catch::Contains("unclosed '{'"));
    CHECK_THROWS_WITH(parse_markup("a}b"), Catch::Contains("unbalanced '}'"));
    CHECK_THROWS_WITH(parse_markup("x^"), Catch::Contains("'^' without an argument"));
    CHECK_NOTHROW(parse_markup("x_{}"));  // an empty group is fine
    CHECK_THROWS_WITH(parse_markup("\\mathrm x"), Catch::Contains("needs a {group}"));
    CHECK_THROWS_WITH(parse_markup("a\\"), Catch::Contains("at the end"));
}

TEST_CASE("markup: a sub- and a superscript in a row stack", "[plot][markup]") {
    const auto runs = parse_markup("t_{run}^{-1} [s]");
    REQUIRE(runs.size() == 4);
    CHECK_FALSE(runs[1].stacked);
    CHECK(runs[2].text == "−1");
    CHECK(runs[2].stacked);
    CHECK_FALSE(runs[3].stacked);
    CHECK(parse_markup("v_x^2")[2].stacked);
    // Not when something comes between.
    const auto apart = parse_markup("v_x y^2");
    CHECK_FALSE(apart.back().stacked);
}

#include "plot/figure.hpp"
#include "plot/text.hpp"

TEST_CASE("markup: DejaVu Sans has a glyph for every command", "[plot][markup][text]") {
    const char* all =
        "\\alpha\\beta\\gamma\\delta\\epsilon\\varepsilon\\zeta\\eta\\theta\\vartheta\\iota\\kappa"
        "\\lambda\\mu\\nu\\xi\\pi\\varpi\\rho\\varrho\\sigma\\varsigma\\tau\\upsilon\\phi\\varphi"
        "\\chi\\psi\\omega\\Gamma\\Delta\\Theta\\Lambda\\Xi\\Pi\\Sigma\\Upsilon\\Phi\\Psi\\Omega"
        "\\nabla\\partial\\infty\\langle\\rangle\\odot\\prime\\ell\\hbar\\degree\\circ\\sqrt\\sum"
        "\\int\\AA\\ldots\\dots\\cdots\\perp\\parallel\\dagger\\uparrow\\downarrow "
        "a\\times b\\cdot c\\pm d\\mp e\\div f\\le g\\leq h\\ge i\\geq j\\ne k\\neq l\\approx "
        "m\\sim n"
        "\\simeq o\\propto p\\equiv q\\ll r\\gg s\\to t\\rightarrow u\\leftarrow v\\Rightarrow w "
        "-1";
    plot::detail::Font font(plot::default_font());
    CHECK(font.missing_glyphs(parse_markup(all)).empty());
    // And the font reports what it lacks.
    CHECK(font.missing_glyphs(parse_markup("\u4E2D")).size() == 1);
}
