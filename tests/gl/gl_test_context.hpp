#pragma once
// One OSMesa core 4.5 context for all GL tests of the executable, current and loaded.
#include <glad/gl.h>

#include <hairshadow/gl/context/osmesa_context.hpp>

#include <catch2/catch.hpp>

namespace test {
inline hairshadow::gl::osmesa_context& gl_context() {
    static hairshadow::gl::osmesa_context ctx(4, 5);
    ctx.make_current();
    // Reloaded on every call: a test of another context (EGL) may have loaded glad with its functions.
    REQUIRE(gladLoadGL(ctx.loader()) != 0);
    return ctx;
}
} // namespace test

#include <hairshadow/gl/context/objects.hpp>
#include <hairshadow/gl/lookup/point_queries.hpp>
#include <hairshadow/hairshadow.hpp>

#include <glm/matrix.hpp>

#include <bit>
#include <cstdint>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

namespace test {

/// Points well inside their texels: the centres of every `step`-th occupied texel, at depths from just
/// in front of its nearest fragment to just behind its furthest.
inline std::vector<glm::vec3> texel_centre_queries(const hairshadow::fragment_buffer& fragments, const hairshadow::light_space& light, int step) {
    std::vector<glm::vec3> queries;
    const glm::mat4 to_world = glm::inverse(light.view_projection());
    const int res = light.resolution();
    for (int y = 1; y < res; y += step)
        for (int x = 1; x < res; x += step) {
            const auto frags = fragments.texel(x, y);
            if (frags.empty()) continue;
            float lo = frags[0].depth, hi = lo;
            for (const auto& f : frags) lo = std::min(lo, f.depth), hi = std::max(hi, f.depth);
            for (float f : {-0.001f, 0.25f, 0.5f, 0.75f, 1.001f}) {
                const float depth = lo + f * (hi - lo);
                const glm::vec4 ndc((float(x) + 0.5f) / float(res) * 2.0f - 1.0f, (float(y) + 0.5f) / float(res) * 2.0f - 1.0f, 2.0f * depth - 1.0f, 1.0f);
                const glm::vec4 w = to_world * ndc;
                queries.push_back(glm::vec3(w) / w.w);
            }
        }
    return queries;
}

/// Runs hs_transmittance(point) in a vertex shader over `points`; `bind` sets the maps' uniforms.
inline std::vector<float> gl_lookup(const std::string& lookup_source, const std::function<void(GLuint)>& bind, const std::vector<glm::vec3>& points) {
    return hairshadow::gl::point_queries(lookup_source).run(points, bind);
}

/// The GLSL look-up of `on_gl` against `cpu`'s query at `queries` (within 1e-4, more than `shadowed_share`
/// of them below 0.9), and the maps read back (on_gl.to_cpu()) answering as `cpu` (within 1e-5).
template <class GlMaps, class Method>
void check_lookup_and_read_back(GlMaps& on_gl, const Method& cpu, const std::vector<glm::vec3>& queries, float shadowed_share) {
    const auto on_gpu = gl_lookup(on_gl.lookup_source(), [&](GLuint p) { on_gl.bind_lookup(p); }, queries);
    std::vector<float> on_cpu(queries.size());
    cpu.transmittance(queries, on_cpu);
    float worst = 0;
    std::size_t shadowed = 0;
    for (std::size_t i = 0; i < queries.size(); ++i) worst = std::max(worst, std::abs(on_gpu[i] - on_cpu[i])), shadowed += on_cpu[i] < 0.9f;
    CAPTURE(worst, queries.size(), shadowed);
    CHECK(queries.size() >= 2000);
    CHECK(float(shadowed) > shadowed_share * float(queries.size()));
    CHECK(worst < 1e-4f);

    const Method back = on_gl.to_cpu();
    std::vector<float> from_back(queries.size());
    back.transmittance(queries, from_back);
    std::size_t differ = 0;
    for (std::size_t i = 0; i < queries.size(); ++i) differ += std::abs(from_back[i] - on_cpu[i]) > 1e-5f;
    CHECK(differ == 0);
}

/// A float from its bits, and back: the words run_on_words moves.
inline float from_bits(std::uint32_t u) { return std::bit_cast<float>(u); }
inline std::uint32_t bits_of(float f) { return std::bit_cast<std::uint32_t>(f); }

/// Runs a compute program over 32-bit words, one invocation per item: `pieces`, then `main_text`,
/// whose main() reads hs_in[] (binding 0, holding `in`) and writes hs_out[] (binding 1, as many
/// words) for item gl_GlobalInvocationID.x below hs_count = `count` (local size 64, declared here).
/// Returns hs_out's words.
inline std::vector<std::uint32_t> run_on_words(const std::string& defines, std::vector<std::string_view> pieces, std::string_view main_text,
                                               const std::vector<std::uint32_t>& in, std::uint32_t count, const std::string& name) {
    gl_context();
    static constexpr std::string_view declarations = R"(
layout(local_size_x = 64) in;
layout(std430, binding = 0) readonly buffer hs_in_block { uint hs_in[]; };
layout(std430, binding = 1) writeonly buffer hs_out_block { uint hs_out[]; };
uniform uint hs_count;
)";
    pieces.push_back(declarations);
    pieces.push_back(main_text);
    const auto stage = hairshadow::gl::compile_stage(GL_COMPUTE_SHADER, defines, std::move(pieces), name);
    const auto program = hairshadow::gl::link_program({&stage}, name);
    auto input = hairshadow::gl::make_buffer(), output = hairshadow::gl::make_buffer();
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, input.get());
    glBufferData(GL_SHADER_STORAGE_BUFFER, GLsizeiptr(in.size() * 4), in.data(), GL_STATIC_DRAW);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, output.get());
    glBufferData(GL_SHADER_STORAGE_BUFFER, GLsizeiptr(in.size() * 4), nullptr, GL_DYNAMIC_READ);
    glUseProgram(program.get());
    glUniform1ui(glGetUniformLocation(program.get(), "hs_count"), count);
    glDispatchCompute((count + 63) / 64, 1, 1);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    std::vector<std::uint32_t> result(in.size());
    glGetBufferSubData(GL_SHADER_STORAGE_BUFFER, 0, GLsizeiptr(result.size() * 4), result.data());
    glUseProgram(0);
    REQUIRE(glGetError() == GL_NO_ERROR);
    return result;
}

} // namespace test
