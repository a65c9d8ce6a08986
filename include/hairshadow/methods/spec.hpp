#pragma once
/// @file
/// Method specs, the text form of a method (`osm:16`, `dom:3`, `occ:128:4:8bit`, `dsm`, ...): parsed,
/// described and turned into methods through the registered families (methods/registered.hpp).

#include <hairshadow/methods/method_family.hpp>
#include <hairshadow/methods/registered.hpp>

#include <algorithm>
#include <string>
#include <tuple>
#include <string_view>
#include <vector>

namespace hairshadow {

namespace detail {
/// The default accumulation's name (the first registered).
inline std::string default_accumulation() {
    std::string name;
    registered_accumulations::any([&]<class A>() { return name = std::string(A::name), true; });
    return name;
}

/// The names of the families whose specs take an accumulation: "osm, dc, dom, occ, fom or ue".
inline std::string accumulating_families() {
    std::vector<std::string_view> names;
    registered_families::any([&]<class F>() {
        if (F::takes_accumulation) names.push_back(F::name);
        return false;
    });
    std::string joined;
    for (std::size_t i = 0; i < names.size(); ++i) joined += (i == 0 ? "" : i + 1 == names.size() ? " or " : ", ") + std::string(names[i]);
    return joined;
}
} // namespace detail

/// The grammar of method specs: every registered family's, and the accumulations that may follow.
inline std::string method_grammar() {
    std::string grammar;
    registered_families::any([&]<class F>() {
        grammar += (grammar.empty() ? "" : " | ") + std::string(F::grammar);
        return false;
    });
    const std::string fallback = detail::default_accumulation();
    registered_accumulations::any([&]<class A>() {
        if (A::name != fallback) grammar += "; append :" + std::string(A::name) + " (" + std::string(A::summary) + ") to " + detail::accumulating_families();
        return false;
    });
    return grammar;
}

/// Parses a method spec; throws spec_error with the grammar on anything else.
inline method_spec parse_method_spec(std::string_view text) {
    method_spec spec;
    spec.text = std::string(text);
    spec.accumulation = detail::default_accumulation();
    for (auto part : detail::split(text, ':')) spec.fields.emplace_back(part);
    spec.family = spec.fields.front();
    spec.fields.erase(spec.fields.begin());
    const auto bad = [&](const std::string& why) {
        return spec_error("bad method spec '" + spec.text + "': " + why + "; valid: " + method_grammar());
    };
    bool named_accumulation = false;
    if (!spec.fields.empty())
        registered_accumulations::any([&]<class A>() {
            if (A::name == spec.accumulation || spec.fields.back() != A::name) return false;
            spec.accumulation = std::string(A::name);
            spec.fields.pop_back();
            return named_accumulation = true;
        });
    const bool known = registered_families::any([&]<class F>() {
        if (spec.family != F::name) return false;
        if (named_accumulation && !F::takes_accumulation) throw bad(":" + spec.accumulation + " applies to " + detail::accumulating_families());
        F::check(spec_fields(spec.text, spec.fields, method_grammar()));
        return true;
    });
    if (!known) throw bad("unknown method '" + spec.family + "'");
    return spec;
}

/// Calls visit(method) with the method of a parsed spec, made with its parameters: a shadow_method,
/// or exact_reference for the exact map. False where the spec names no registered method.
template <class Visit>
bool visit_method(const method_spec& spec, Visit&& visit) {
    return registered_families::any([&]<class F>() {
        if (spec.family != F::name) return false;
        const spec_fields fields(spec.text, spec.fields, F::grammar);
        return registered_accumulations::any([&]<class A>() { return spec.accumulation == A::name && F::template visit<A>(fields, visit); });
    });
}

/// Calls visit(example) for every registered family's spec_example, in the registry's order (for
/// tests: example.spec, and typename decltype(example)::method_type).
template <class Visit>
void for_each_example(Visit&& visit) {
    registered_families::any([&]<class F>() {
        std::apply([&](const auto&... example) { (visit(example), ...); }, F::examples);
        return false;
    });
}

/// The registered families' example specs in `list` (spec_lists; in_tests: all of them), in the
/// registry's order.
inline std::vector<std::string> example_specs(spec_lists list = in_tests) {
    std::vector<std::string> specs;
    for_each_example([&](const auto& e) {
        if (list == in_tests || (e.lists & list)) specs.emplace_back(e.spec);
    });
    return specs;
}

/// The words of method specs, for a fuzzer's dictionary: every registered family's name and keywords,
/// the accumulations' names but the default's, the field separator, and every field of the families'
/// examples; each once, in the registry's order.
inline std::vector<std::string> method_spec_tokens() {
    std::vector<std::string> tokens{":"};
    const auto add = [&](std::string_view t) {
        if (!t.empty() && std::find(tokens.begin(), tokens.end(), t) == tokens.end()) tokens.emplace_back(t);
    };
    registered_families::any([&]<class F>() {
        add(F::name);
        for (const auto keyword : F::keywords) add(keyword);
        return false;
    });
    const std::string fallback = detail::default_accumulation();
    registered_accumulations::any([&]<class A>() {
        if (A::name != fallback) add(A::name);
        return false;
    });
    for (const auto& example : example_specs())
        for (const auto field : detail::split(example, ':')) add(field);
    return tokens;
}

/// Whether a parsed spec names the exact reference, which only the CPU builds.
inline bool names_exact_reference(const method_spec& spec) { return spec.family == exact_reference_family::name; }

/// example_specs(list) joined by commas: a default of the command line's --methods.
inline std::string example_spec_list(spec_lists list) {
    std::string joined;
    for (const auto& s : example_specs(list)) joined += (joined.empty() ? "" : ",") + s;
    return joined;
}

} // namespace hairshadow
