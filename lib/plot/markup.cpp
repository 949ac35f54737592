/// \file
/// \brief The label markup parser: TeX-like commands, scripts and groups -> runs of text.
#include "plot/markup.hpp"

#include "plot/error.hpp"

#include <array>
#include <cctype>
#include <utility>

namespace plot {
namespace {

/// How a command's symbol is spaced: as a letter, a binary operator or a relation.
enum class Spacing { ordinary, binary, relation };

struct Symbol {
    std::string_view name;
    std::string_view utf8;
    Spacing spacing = Spacing::ordinary;
};

// Greek letters follow TeX: \epsilon and \phi are the lunate and the closed forms,
// \varepsilon and \varphi the open ones.
constexpr std::array symbols{
    Symbol{"alpha", "α"},
    Symbol{"beta", "β"},
    Symbol{"gamma", "γ"},
    Symbol{"delta", "δ"},
    Symbol{"epsilon", "ϵ"},
    Symbol{"varepsilon", "ε"},
    Symbol{"zeta", "ζ"},
    Symbol{"eta", "η"},
    Symbol{"theta", "θ"},
    Symbol{"vartheta", "ϑ"},
    Symbol{"iota", "ι"},
    Symbol{"kappa", "κ"},
    Symbol{"lambda", "λ"},
    Symbol{"mu", "μ"},
    Symbol{"nu", "ν"},
    Symbol{"xi", "ξ"},
    Symbol{"pi", "π"},
    Symbol{"varpi", "ϖ"},
    Symbol{"rho", "ρ"},
    Symbol{"varrho", "ϱ"},
    Symbol{"sigma", "σ"},
    Symbol{"varsigma", "ς"},
    Symbol{"tau", "τ"},
    Symbol{"upsilon", "υ"},
    Symbol{"phi", "ϕ"},
    Symbol{"varphi", "φ"},
    Symbol{"chi", "χ"},
    Symbol{"psi", "ψ"},
    Symbol{"omega", "ω"},
    Symbol{"Gamma", "Γ"},
    Symbol{"Delta", "Δ"},
    Symbol{"Theta", "Θ"},
    Symbol{"Lambda", "Λ"},
    Symbol{"Xi", "Ξ"},
    Symbol{"Pi", "Π"},
    Symbol{"Sigma", "Σ"},
    Symbol{"Upsilon", "Υ"},
    Symbol{"Phi", "Φ"},
    Symbol{"Psi", "Ψ"},
    Symbol{"Omega", "Ω"},
    // Symbols set as letters.
    Symbol{"nabla", "∇"},
    Symbol{"partial", "∂"},
    Symbol{"infty", "∞"},
    Symbol{"langle", "⟨"},
    Symbol{"rangle", "⟩"},
    Symbol{"odot", "⊙"},
    Symbol{"prime", "′"},
    Symbol{"ell", "ℓ"},
    Symbol{"hbar", "ℏ"},
    Symbol{"degree", "°"},
    Symbol{"circ", "∘"},
    Symbol{"sqrt", "√"},
    Symbol{"sum", "∑"},
    Symbol{"int", "∫"},
    Symbol{"AA", "Å"},
    Symbol{"ldots", "…"},
    Symbol{"dots", "…"},
    Symbol{"cdots", "⋯"},
    Symbol{"perp", "⊥"},
    Symbol{"parallel", "∥"},
    Symbol{"dagger", "†"},
    Symbol{"uparrow", "↑"},
    Symbol{"downarrow", "↓"},
    // Binary operators.
    Symbol{"times", "×", Spacing::binary},
    Symbol{"cdot", "⋅", Spacing::binary},
    Symbol{"pm", "±", Spacing::binary},
    Symbol{"mp", "∓", Spacing::binary},
    Symbol{"div", "÷", Spacing::binary},
    // Relations.
    Symbol{"le", "≤", Spacing::relation},
    Symbol{"leq", "≤", Spacing::relation},
    Symbol{"ge", "≥", Spacing::relation},
    Symbol{"geq", "≥", Spacing::relation},
    Symbol{"ne", "≠", Spacing::relation},
    Symbol{"neq", "≠", Spacing::relation},
    Symbol{"approx", "≈", Spacing::relation},
    Symbol{"sim", "∼", Spacing::relation},
    Symbol{"simeq", "≃", Spacing::relation},
    Symbol{"propto", "∝", Spacing::relation},
    Symbol{"equiv", "≡", Spacing::relation},
    Symbol{"ll", "≪", Spacing::relation},
    Symbol{"gg", "≫", Spacing::relation},
    Symbol{"to", "→", Spacing::relation},
    Symbol{"rightarrow", "→", Spacing::relation},
    Symbol{"leftarrow", "←", Spacing::relation},
    Symbol{"Rightarrow", "⇒", Spacing::relation},
};

// Spaces by their width, so the text layout need not trust the font for them.
constexpr std::string_view thin_space = "\u2006";      // 1/6 em, TeX's \,
constexpr std::string_view binary_space = "\u2005";    // 1/4 em, TeX's medium space
constexpr std::string_view relation_space = "\u2004";  // 1/3 em, TeX's thick space
constexpr std::string_view minus_sign = "\u2212";

// Script geometry, relative to the enclosing level's size.
constexpr double script_scale = 0.70;
constexpr double superscript_shift = 0.42;
constexpr double subscript_shift = -0.20;

/// One nesting level of the markup: its baseline and size.
struct Level {
    double shift = 0.0;
    double scale = 1.0;
};

class Parser {
  public:
    explicit Parser(std::string_view source) : source_(source) {}

    std::vector<TextRun> parse() {
        parse_sequence(Level{}, false);
        return std::move(runs_);
    }

  private:
    std::string_view source_;
    std::size_t pos_ = 0;
    std::vector<TextRun> runs_;
    char previous_ = '\0';      ///< last character emitted in the current group ('\0' at start)
    bool skip_spaces_ = false;  ///< set after an operator: its own spacing replaces typed spaces
    // The script just parsed, so that a script of the other kind right after it can stack.
    std::size_t script_end_ = std::string_view::npos;  ///< position after it
    std::size_t script_runs_ = 0;                      ///< runs it made
    bool script_was_super_ = false;
    bool stack_next_ = false;  ///< the next emitted text starts a stacked run

    [[noreturn]] void fail(const std::string& what) const {
        throw Error("markup: " + what + " in \"" + std::string(source_) + "\"");
    }

    bool at_end() const { return pos_ >= source_.size(); }
    char peek() const { return source_[pos_]; }

    // ---- Output ------------------------------------------------------------------------------
    void emit(std::string_view text, const Level& level) {
        if (text.empty()) return;
        if (!stack_next_ && !runs_.empty() && runs_.back().shift == level.shift &&
            runs_.back().scale == level.scale) {
            runs_.back().text += text;
        } else {
            runs_.push_back({std::string(text), level.shift, level.scale, stack_next_});
        }
        stack_next_ = false;
        previous_ = text.back();
    }

    void strip_trailing_spaces() {
        while (!runs_.empty()) {
            std::string& text = runs_.back().text;
            while (!text.empty() && text.back() == ' ') text.pop_back();
            if (!text.empty()) break;
            runs_.pop_back();
        }
    }

    // ---- Grammar -----------------------------------------------------------------------------
    /// A sequence of characters, commands, scripts and groups, up to '}' (in a group) or the end.
    void parse_sequence(const Level& level, bool in_group) {
        previous_ = '\0';
        while (!at_end()) {
            const char c = peek();
            if (c == '}') {
                if (!in_group) fail("unbalanced '}' at position " + std::to_string(pos_));
                return;
            }
            parse_item(level);
        }
        if (in_group) fail("unclosed '{'");
    }

    /// One item: a group, a script, a command or a plain (UTF-8) character.
    void parse_item(const Level& level) {
        const char c = peek();
        if (c == ' ' && skip_spaces_) {
            ++pos_;
            return;
        }
        skip_spaces_ = false;
        if (c == '{') {
            parse_group(level);
        } else if (c == '^' || c == '_') {
            ++pos_;
            parse_script(level, c == '^');
        } else if (c == '\\') {
            parse_command(level);
        } else if (c == '-' && starts_number() && minus_allowed_here()) {
            ++pos_;
            emit(minus_sign, level);
        } else {
            emit(take_code_point(), level);
        }
    }

    void parse_group(const Level& level) {
        ++pos_;  // '{'
        parse_sequence(level, true);
        ++pos_;  // '}'
    }

    void parse_script(const Level& parent, bool superscript) {
        const Level level{
            parent.shift + parent.scale * (superscript ? superscript_shift : subscript_shift),
            parent.scale * script_scale};
        const char* name = superscript ? "'^'" : "'_'";
        if (at_end() || peek() == '}') fail(std::string(name) + " without an argument");
        // A superscript right after a one-run subscript (or the reverse) stacks over it.
        stack_next_ =
            pos_ - 1 == script_end_ && script_runs_ == 1 && script_was_super_ != superscript;
        const std::size_t runs_before = runs_.size();
        if (peek() == '{') {
            parse_group(level);
        } else if (peek() == '\\') {
            previous_ = '\0';
            parse_command(level);
        } else {
            previous_ = '\0';
            if (peek() == '-' && starts_number()) {
                ++pos_;
                emit(minus_sign, level);
            } else {
                emit(take_code_point(), level);
            }
        }
        stack_next_ = false;
        script_end_ = pos_;
        script_runs_ = runs_.size() - runs_before;
        script_was_super_ = superscript;
    }

    void parse_command(const Level& level) {
        ++pos_;  // '\'
        if (at_end()) fail("'\\' at the end");
        const std::size_t start = pos_;
        while (!at_end() && std::isalpha(static_cast<unsigned char>(peek()))) ++pos_;
        if (pos_ == start) {
            parse_control_symbol(level);
            return;
        }
        const std::string_view name = source_.substr(start, pos_ - start);
        if (name == "mathrm" || name == "text" || name == "mathit" || name == "mathbf" ||
            name == "rm") {
            if (at_end() || peek() != '{') fail("\\" + std::string(name) + " needs a {group}");
            parse_group(level);
            return;
        }
        for (const Symbol& symbol : symbols) {
            if (symbol.name == name) {
                emit_symbol(symbol, level);
                return;
            }
        }
        fail("unknown command \\" + std::string(name));
    }

    /// A backslash followed by one non-letter: spacing and escaped characters.
    void parse_control_symbol(const Level& level) {
        const char c = peek();
        ++pos_;
        switch (c) {
            case ',':
                emit(thin_space, level);
                return;
            case ' ':
                emit(" ", level);
                return;
            case '{':
            case '}':
            case '\\':
            case '_':
            case '^':
            case '%':
            case '$':
            case '#':
            case '&':
                emit(std::string_view(&c, 1), level);
                return;
            default:
                fail(std::string("unknown command \\") + c);
        }
    }

    void emit_symbol(const Symbol& symbol, const Level& level) {
        if (symbol.spacing == Spacing::ordinary) {
            emit(symbol.utf8, level);
            return;
        }
        strip_trailing_spaces();
        const bool unary = symbol.spacing == Spacing::binary &&
                           (previous_ == '\0' || previous_ == '(' || previous_ == '[' ||
                            previous_ == '=' || previous_ == ',');
        const std::string_view space =
            unary ? std::string_view{}
                  : (symbol.spacing == Spacing::binary ? binary_space : relation_space);
        // A relation opening a group has nothing on its left to keep apart from.
        if (previous_ != '\0') emit(space, level);
        emit(symbol.utf8, level);
        emit(space, level);
        skip_spaces_ = true;
    }

    // ---- Characters ----------------------------------------------------------------------
    bool starts_number() const {
        if (pos_ + 1 >= source_.size()) return false;
        const char next = source_[pos_ + 1];
        return std::isdigit(static_cast<unsigned char>(next)) || next == '.';
    }

    bool minus_allowed_here() const {
        return previous_ == '\0' || previous_ == ' ' || previous_ == '(' || previous_ == '[' ||
               previous_ == '=' || previous_ == ',' || previous_ == '/';
    }

    /// The next UTF-8 encoded code point, whole.
    std::string_view take_code_point() {
        const auto lead = static_cast<unsigned char>(peek());
        std::size_t length = 1;
        if (lead >= 0xF0)
            length = 4;
        else if (lead >= 0xE0)
            length = 3;
        else if (lead >= 0xC0)
            length = 2;
        length = std::min(length, source_.size() - pos_);
        const std::string_view cp = source_.substr(pos_, length);
        pos_ += length;
        return cp;
    }
};

}  // namespace

std::vector<TextRun> parse_markup(std::string_view markup) { return Parser(markup).parse(); }

std::string plain_text(const std::vector<TextRun>& runs) {
    std::string text;
    for (const TextRun& run : runs) text += run.text;
    return text;
}

}  // namespace plot
