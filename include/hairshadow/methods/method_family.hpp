#pragma once
/// @file
/// What a method registers once, beside it: a method family (`dom`, `occ`, ...) names its spec, says
/// its grammar, checks a spec's fields and turns a spec into the method, with its parameters. The
/// spec parser, the run-time registries (CPU and GL), the command line's lists, the fuzz dictionary
/// and the tests' lists of methods all read the families registered in methods/registered.hpp.
///
/// A family is a type with:
/// - `name`: the spec's first field (`"dom"`), and `grammar`: its help text (`"dom:K (K = 1..8)"`);
/// - `examples`: a tuple of spec_example, specs of it with the methods they make and the command
///   line's lists they appear in (the tests take every one);
/// - `keywords`: the words its specs may hold besides numbers (for the fuzz dictionary);
/// - `takes_accumulation`: whether a spec may end in another accumulation's name (`:8bit`);
/// - `check(fields)`: throws spec_error unless the fields after the name are valid;
/// - `visit<Accumulation>(fields, visit)`: calls visit(method) with the method of valid fields,
///   made with their parameters (a shadow_method, or exact_reference for the exact map).

#include <hairshadow/core/error.hpp>
#include <hairshadow/core/parse.hpp>

#include <array>
#include <concepts>
#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <tuple>
#include <type_traits>
#include <utility>
#include <vector>

namespace hairshadow {

/// A bad method spec; what() quotes the valid grammar.
class spec_error : public argument_error {
public:
    using argument_error::argument_error;
};

/// A parsed method spec: the family's name, the fields after it as written, and the accumulation, a
/// parameter like the others: a registered accumulation's name, the default one's ("float") unless
/// the spec ends in another's (`:8bit`).
struct method_spec {
    std::string text;                ///< the spec as given
    std::string family;              ///< a registered family's name
    std::vector<std::string> fields; ///< the fields after the name, the accumulation's left out ("128", "4" for occ:128:4:8bit)
    std::string accumulation;        ///< a registered accumulation's name ("float", "8bit")
    friend bool operator==(const method_spec&, const method_spec&) = default;
};

/// The exact reference, as a family's visit gives it: a deep shadow map, compressed to `tolerance`
/// (Lokovic-Veach) where one is given.
struct exact_reference {
    std::optional<float> tolerance;
};

/// Where a family's example spec appears, besides the tests (which take every example).
enum spec_lists : unsigned {
    in_tests = 0,       ///< the tests' lists only
    in_compare = 1,     ///< `hairshadow compare`'s default methods
    in_bench = 2,       ///< `hairshadow bench`'s
    in_figure = 4,      ///< the comparison figure's panels
    in_animate = 8,     ///< `hairshadow animate`'s panels
};

/// A spec a family gives as an example, the method it makes (with default parameters, which the
/// spec's must be) and the command line's default lists it is in (spec_lists).
template <class Method>
struct spec_example {
    using method_type = Method;
    std::string_view spec;
    unsigned lists = in_tests;
};

/// The fields of a spec after its name, read for a family: each reader throws spec_error with the
/// family's reason and the grammar where a field is not what the family needs.
class spec_fields {
public:
    spec_fields(std::string_view text, std::span<const std::string> fields, std::string_view grammar) noexcept
        : text_(text), fields_(fields), grammar_(grammar) {}

    std::size_t size() const noexcept { return fields_.size(); }
    std::string_view operator[](std::size_t i) const noexcept { return fields_[i]; }

    /// A spec_error saying why the spec is bad, with the valid grammar.
    spec_error bad(const std::string& why) const {
        return spec_error("bad method spec '" + std::string(text_) + "': " + why + "; valid: " + std::string(grammar_));
    }
    /// Field i as a count: a whole number written as one would say it, with no sign and no leading
    /// zero (dom:03 is a typo).
    int whole(std::size_t i) const {
        const std::string_view s = fields_[i];
        if (s.size() > 1 && s[0] == '0') throw bad("'" + std::string(s) + "' has a leading zero");
        try {
            return detail::parse_number<int>(s, "count");
        } catch (const argument_error&) {
            throw bad("'" + std::string(s) + "' is not a whole number");
        }
    }
    /// Field i as a finite real number; `what` names it in the error.
    float real(std::size_t i, std::string_view what) const {
        try {
            return detail::parse_number<float>(fields_[i], what);
        } catch (const argument_error&) {
            throw bad("the " + std::string(what) + " '" + std::string(fields_[i]) + "' is not a number");
        }
    }

    /// Runs `check`, which validates parameters made from these fields, and turns the
    /// argument_error it throws into this spec's spec_error.
    template <class Check>
    void checked(Check&& check) const {
        try {
            check();
        } catch (const spec_error&) {
            throw;
        } catch (const argument_error& e) {
            throw bad(e.what());
        }
    }

private:
    std::string_view text_;
    std::span<const std::string> fields_;
    std::string_view grammar_;
};

/// Allowed values of a family's size parameter, in a list that with_size dispatches on.
template <int... Sizes>
struct size_list {
    static constexpr std::array<int, sizeof...(Sizes)> values{Sizes...};
    static constexpr bool contains(int n) noexcept { return ((n == Sizes) || ...); }
};

/// Calls visit(std::integral_constant<int, n>) for the n of `Sizes` equal to `value`; false if none is.
template <class Sizes, std::size_t I = 0, class Visit>
bool with_size(int value, Visit&& visit) {
    if constexpr (I == Sizes::values.size()) {
        return false;
    } else {
        if (value == Sizes::values[I]) return visit(std::integral_constant<int, Sizes::values[I]>{}), true;
        return with_size<Sizes, I + 1>(value, visit);
    }
}

/// What a method family provides (see the file's comment).
template <class F>
concept method_family = requires(const spec_fields& fields) {
    { F::name } -> std::convertible_to<std::string_view>;
    { F::grammar } -> std::convertible_to<std::string_view>;
    { F::takes_accumulation } -> std::convertible_to<bool>;
    std::tuple_size<std::remove_const_t<decltype(F::examples)>>::value;
    F::keywords.size();
    F::check(fields);
};

/// The families a registry knows, in the order its lists give them.
template <method_family... Families>
struct family_list {
    /// Calls f.template operator()<Family>() for each family, in order, until it returns true;
    /// whether one did.
    template <class F>
    static bool any(F&& f) {
        return (f.template operator()<Families>() || ...);
    }
};

/// The accumulations a spec may name by their `name` as its last field (the first is the default,
/// written without one).
template <class... Accumulations>
struct accumulation_list {
    template <class F>
    static bool any(F&& f) {
        return (f.template operator()<Accumulations>() || ...);
    }
};

} // namespace hairshadow
