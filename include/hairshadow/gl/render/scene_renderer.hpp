#pragma once
/// @file
/// The GL renderer: the same scene description as render_cpu, drawn with multisampled lines. One
/// pass per light, added by blending: each pass's programs are composed from that light's method
/// look-up (hs_transmittance) and the shading snippets (shaders/render/), so Kajiya-Kay hair (at
/// the strand points) and Lambert mesh (per pixel) see the hair's transmittance and the mesh's depth
/// shadow map, which is drawn on GL too. Transparent hair (set_transparency) is blended over the
/// mesh by gl::transparent_hair.

#include <hairshadow/gl/context/context.hpp>
#include <hairshadow/gl/lookup/lookup_binding.hpp>
#include <hairshadow/gl/passes/hair_mesh.hpp>
#include <hairshadow/gl/context/objects.hpp>
#include <hairshadow/gl/context/state_guard.hpp>
#include <hairshadow/gl/shaders.generated.hpp>
#include <hairshadow/gl/render/transparent_hair.hpp>
#include <hairshadow/shading/camera.hpp>
#include <hairshadow/shading/cpu_renderer.hpp>
#include <hairshadow/shading/image.hpp>
#include <hairshadow/shading/scene.hpp>

#include <glm/vec4.hpp>

#include <functional>
#include <limits>
#include <memory>
#include <utility>
#include <string>
#include <vector>

namespace hairshadow::gl {

/// Draws a scene on the current GL 4.3+ context.
class scene_renderer {
public:
    /// Uploads the hair (points and tangents) and the mesh (vertices and smooth normals).
    explicit scene_renderer(const scene& sc) : scene_(sc) {
        require_version(4, 3, "the GL renderer");
        const std::vector<float> hair = hair_vertices();
        std::vector<std::uint32_t> lines;
        for (std::size_t s = 0; s < sc.hair.strand_count(); ++s)
            for (std::uint32_t i = sc.hair.strand_offsets[s]; i + 1 < sc.hair.strand_offsets[s + 1]; ++i) lines.insert(lines.end(), {i, i + 1});
        upload(hair_, hair, lines);
        hair_count_ = GLsizei(lines.size());
        hair_floats_ = hair.size();
        const auto normals = hairshadow::detail::vertex_normals(sc.mesh);
        std::vector<float> mesh;
        for (std::size_t i = 0; i < sc.mesh.vertices.size(); ++i)
            mesh.insert(mesh.end(), {sc.mesh.vertices[i].x, sc.mesh.vertices[i].y, sc.mesh.vertices[i].z, normals[i].x, normals[i].y, normals[i].z});
        std::vector<std::uint32_t> triangles;
        for (const auto& t : sc.mesh.triangles)
            if (t[0] < sc.mesh.vertices.size() && t[1] < sc.mesh.vertices.size() && t[2] < sc.mesh.vertices.size()) triangles.insert(triangles.end(), t.begin(), t.end());
        upload(mesh_, mesh, triangles);
        mesh_count_ = GLsizei(triangles.size());
        const auto vs = compile_stage(GL_VERTEX_SHADER, {}, {shaders::raster_vertex}, "raster/vertex");
        const auto fs = compile_stage(GL_FRAGMENT_SHADER, {}, {shaders::render_mesh_depth}, "render/mesh_depth");
        depth_program_ = link_program({&vs, &fs}, "mesh depth pass");
    }

    /// Reads the scene's hair points again after the hair moved (the same strands, points moved in
    /// place: gl::hair_mesh::update's twin for the camera's passes). Throws argument_error if the
    /// point count changed.
    void update_hair() {
        const std::vector<float> hair = hair_vertices();
        if (hair.size() != hair_floats_) throw argument_error("scene_renderer::update_hair: the hair's point count changed");
        if (hair.empty()) return;
        state_guard guard("hairshadow: scene renderer hair update");
        glBindBuffer(GL_ARRAY_BUFFER, hair_.vertices.get());
        glBufferSubData(GL_ARRAY_BUFFER, 0, GLsizeiptr(hair.size() * sizeof(float)), hair.data());
        check("scene_renderer::update_hair");
    }

    /// Adds a light whose hair shadows come from `maps` (a built gl::maps<Method>, kept alive by the
    /// caller) seen from `light`'s frustum: maps.light(). The mesh's depth map is drawn now.
    template <class Maps>
    void add_light(const scene_light& light, const Maps& maps, float mesh_bias = default_mesh_bias) {
        lights_.push_back(make_entry(light, maps.light(), maps.lookup_source(), [&maps](GLuint prog) { maps.bind_lookup(prog, 0); }, mesh_bias));
    }
    /// Adds a light whose hair casts no shadow (the mesh still does), with `space` its frustum.
    void add_unshadowed_light(const scene_light& light, const light_space& space, float mesh_bias = default_mesh_bias) {
        lights_.push_back(unshadowed_entry(light, space, mesh_bias));
    }

    /// How render_into, render and present draw the hair. transparency::none (the default) draws it
    /// opaque, anti-aliased by multisampling. The other modes give each strand alpha `opacity` over
    /// the pixels its `line_width`-pixel line covers, blended by gl::transparent_hair over the mesh,
    /// which is then single-sampled, as hairshadow::render_transparent draws it.
    void set_transparency(transparency mode, float opacity = 0.4f, float line_width = 1.0f) {
        if (!(opacity > 0.0f && opacity <= 1.0f)) throw argument_error("hair opacity must be in (0, 1]");
        if (!(line_width > 0.0f && line_width <= 64.0f)) throw argument_error("hair line width must be in (0, 64] pixels");
        if (mode != transparency::none) transparent_hair::check_support();
        transparency_ = mode;
        hair_opacity_ = opacity;
        line_width_ = line_width;
    }
    transparency transparency_mode() const noexcept { return transparency_; }
    /// Depth-peeling layers of the last render with transparency::exact (a draw of the hair each, and two more).
    int peeled_layers() const noexcept { return peeled_layers_; }

    /// Draws the scene from `cam` into the bound framebuffer (viewport and clearing are the caller's);
    /// `with_hair` false draws the mesh alone (the hair still shadows it). Always opaque hair.
    /// Without lights, the mesh and hair show their ambient terms, as on the CPU.
    void draw(const camera& cam, bool with_hair = true) const {
        const caller_errors_kept kept; // the caller's unread errors stay theirs, and fail nothing here
        const auto& lights = passes();
        glEnable(GL_DEPTH_TEST);
        glEnable(GL_MULTISAMPLE);
        glDisable(GL_BLEND);
        glDisable(GL_RASTERIZER_DISCARD);
        glDisable(GL_COLOR_LOGIC_OP);
        glBlendEquation(GL_FUNC_ADD);
        for (std::size_t i = 0; i < lights.size(); ++i) {
            const auto& l = lights[i];
            // Later passes add their light where the first pass left the nearest surface.
            glDepthFunc(i == 0 ? GL_LESS : GL_LEQUAL);
            if (i == 1) {
                glEnable(GL_BLEND);
                glBlendFunc(GL_ONE, GL_ONE);
                glDepthMask(GL_FALSE);
            }
            for (const auto* p : {&l.mesh_program, &l.hair_program}) {
                glUseProgram(p->get());
                set_pass_uniforms(p->get(), l, cam, i == 0);
                if (p == &l.mesh_program) draw_elements(mesh_, GL_TRIANGLES, mesh_count_);
                else if (with_hair) draw_elements(hair_, GL_LINES, hair_count_);
            }
        }
        glDepthMask(GL_TRUE);
        glDepthFunc(GL_LESS);
        glDisable(GL_BLEND);
        check("scene renderer draw");
    }

    /// Draws the scene with `samples` multisamples off screen and resolves it (the samples' average:
    /// the lines' coverage) into framebuffer `target` (0: the window's), over the whole viewport.
    /// With transparent hair (set_transparency), the passes of gl::transparent_hair draw it instead.
    void render_into(const camera& cam, GLuint target, int samples = 8) const {
        const caller_errors_kept kept; // the caller's unread errors stay theirs, and fail nothing here
        camera::check_image_size(cam.width, cam.height);
        // State a caller may have left that would keep the new buffers from being cleared.
        glDepthMask(GL_TRUE);
        glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
        glDisable(GL_SCISSOR_TEST);
        if (transparency_ != transparency::none) return render_transparent_into(cam, target);
        GLint max_samples = 1;
        glGetIntegerv(GL_MAX_SAMPLES, &max_samples);
        samples = std::clamp(samples, 1, int(max_samples));
        auto colour = make_renderbuffer(), depth = make_renderbuffer();
        glBindRenderbuffer(GL_RENDERBUFFER, colour.get());
        glRenderbufferStorageMultisample(GL_RENDERBUFFER, samples, GL_RGBA32F, cam.width, cam.height);
        glBindRenderbuffer(GL_RENDERBUFFER, depth.get());
        glRenderbufferStorageMultisample(GL_RENDERBUFFER, samples, GL_DEPTH_COMPONENT32F, cam.width, cam.height);
        auto fbo = make_framebuffer();
        glBindFramebuffer(GL_FRAMEBUFFER, fbo.get());
        glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, colour.get());
        glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depth.get());
        clear_and_draw(cam, true);
        glBindFramebuffer(GL_DRAW_FRAMEBUFFER, target);
        glBindFramebuffer(GL_READ_FRAMEBUFFER, fbo.get());
        glBlitFramebuffer(0, 0, cam.width, cam.height, 0, 0, cam.width, cam.height, GL_COLOR_BUFFER_BIT, GL_NEAREST);
        glBindFramebuffer(GL_FRAMEBUFFER, 0);
        check("scene renderer resolve");
    }

    /// Renders off screen with `samples` multisamples and reads the image back.
    image render(const camera& cam, int samples = 8) const {
        const caller_errors_kept kept; // the caller's unread errors stay theirs, and fail nothing here
        camera::check_image_size(cam.width, cam.height);
        const auto [single, resolved] = linear_target(cam.width, cam.height);
        render_into(cam, resolved.get(), samples);
        std::vector<float> rgba(4 * std::size_t(cam.width) * std::size_t(cam.height));
        glBindTexture(GL_TEXTURE_2D, single.get());
        glGetTexImage(GL_TEXTURE_2D, 0, GL_RGBA, GL_FLOAT, rgba.data());
        check("scene renderer read-back");
        image out(cam.width, cam.height, scene_.background);
        for (int y = 0; y < cam.height; ++y)
            for (int x = 0; x < cam.width; ++x) {
                const float* p = &rgba[4 * (std::size_t(cam.height - 1 - y) * std::size_t(cam.width) + std::size_t(x))];
                out.at(x, y) = glm::vec3(p[0], p[1], p[2]);
            }
        return out;
    }

    /// Draws the scene into framebuffer `target` (0: the window's) encoded as sRGB for display: the
    /// multisampled render resolved into a linear texture, then encoded by a full-screen pass.
    void present(const camera& cam, GLuint target, int samples = 4) {
        const caller_errors_kept kept; // the caller's unread errors stay theirs, and fail nothing here
        camera::check_image_size(cam.width, cam.height);
        if (!present_program_.get()) {
            const auto vs = compile_stage(GL_VERTEX_SHADER, {}, {shaders::passes_fullscreen_vertex}, "passes/fullscreen_vertex");
            const auto fs = compile_stage(GL_FRAGMENT_SHADER, {}, {shaders::render_present}, "render/present");
            present_program_ = link_program({&vs, &fs}, "present");
        }
        const auto [linear, resolved] = linear_target(cam.width, cam.height);
        render_into(cam, resolved.get(), samples);
        glBindFramebuffer(GL_FRAMEBUFFER, target);
        glViewport(0, 0, cam.width, cam.height);
        glDisable(GL_DEPTH_TEST);
        glUseProgram(present_program_.get());
        glActiveTexture(GL_TEXTURE0);
        glBindTexture(GL_TEXTURE_2D, linear.get());
        glUniform1i(glGetUniformLocation(present_program_.get(), "hs_linear_image"), 0);
        glBindVertexArray(empty_vao_.get());
        glDrawArrays(GL_TRIANGLES, 0, 3);
        glBindVertexArray(0);
        check("scene renderer present");
    }

    /// Removes every light (to add them again after the maps or the lights change); the scene is
    /// then drawn with its ambient terms alone.
    void clear_lights() { lights_.clear(); }

private:
    /// The mesh's depth map sits on the last of the 16 units GL 4.3 guarantees, clear of any look-up's.
    static constexpr int mesh_depth_unit = 15;

    /// Points and tangents of the scene's hair, six floats a point.
    std::vector<float> hair_vertices() const {
        const auto& h = scene_.hair;
        const auto tangents = hairshadow::detail::strand_tangents(h);
        std::vector<float> hair;
        hair.reserve(6 * h.point_count());
        for (std::size_t i = 0; i < h.point_count(); ++i)
            hair.insert(hair.end(), {h.points[i].x, h.points[i].y, h.points[i].z, tangents[i].x, tangents[i].y, tangents[i].z});
        return hair;
    }

    struct geometry {
        vertex_array vao = make_vertex_array();
        buffer vertices = make_buffer(), indices = make_buffer();
    };
    struct light_entry {
        scene_light light;
        light_space space;
        std::string lookup; ///< the method's look-up source
        std::function<void(GLuint)> bind_lookup;
        float mesh_bias;
        texture mesh_depth;
        program mesh_program, hair_program;
        mutable program colour_program; ///< transparent hair's colours, compiled at the first use
    };

    /// A single-sampled texture (RGBA32F unless told) and a framebuffer drawing into it.
    static std::pair<texture, framebuffer> linear_target(int width, int height, GLenum format = GL_RGBA32F) {
        auto t = make_texture_2d(format, width, height);
        auto f = make_framebuffer();
        glBindFramebuffer(GL_FRAMEBUFFER, f.get());
        glFramebufferTexture(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, t.get(), 0);
        return {std::move(t), std::move(f)};
    }

    static void upload(geometry& g, const std::vector<float>& vertices, const std::vector<std::uint32_t>& indices) {
        glBindVertexArray(g.vao.get());
        glBindBuffer(GL_ARRAY_BUFFER, g.vertices.get());
        glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(vertices.size() * sizeof(float)), vertices.data(), GL_STATIC_DRAW);
        glEnableVertexAttribArray(0);
        glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 6 * sizeof(float), nullptr);
        glEnableVertexAttribArray(1);
        glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, 6 * sizeof(float), reinterpret_cast<void*>(3 * sizeof(float)));
        glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, g.indices.get());
        glBufferData(GL_ELEMENT_ARRAY_BUFFER, GLsizeiptr(indices.size() * sizeof(std::uint32_t)), indices.data(), GL_STATIC_DRAW);
        glBindVertexArray(0);
    }
    static void draw_elements(const geometry& g, GLenum mode, GLsizei count) {
        if (count == 0) return;
        glBindVertexArray(g.vao.get());
        glDrawElements(mode, count, GL_UNSIGNED_INT, nullptr);
        glBindVertexArray(0);
    }
    light_entry make_entry(const scene_light& light, const light_space& space, const std::string& lookup, std::function<void(GLuint)> bind,
                           float bias) const {
        light_entry e{light, space, lookup, std::move(bind), bias, draw_mesh_depth(space), {}, {}, {}};
        const auto mesh_vs = compile_stage(GL_VERTEX_SHADER, {}, {shaders::render_mesh_vertex}, "render/mesh_vertex");
        const auto mesh_fs = compile_stage(GL_FRAGMENT_SHADER, {}, {lookup, shaders::render_light, shaders::render_mesh_fragment}, "render/mesh_fragment");
        const auto hair_vs = compile_stage(GL_VERTEX_SHADER, {}, {lookup, shaders::render_light, shaders::render_hair_shading, shaders::render_hair_vertex},
                                            "render/hair_vertex");
        const auto hair_fs = compile_stage(GL_FRAGMENT_SHADER, {}, {shaders::render_hair_fragment}, "render/hair_fragment");
        e.mesh_program = link_program({&mesh_vs, &mesh_fs}, "mesh shading");
        e.hair_program = link_program({&hair_vs, &hair_fs}, "hair shading");
        return e;
    }
    light_entry unshadowed_entry(const scene_light& light, const light_space& space, float bias) const {
        // The light's frustum (lookup/light.glsl, which the mesh's depth test reads) and no hair.
        const std::string no_hair =
            std::string(shaders::arithmetic_exact_division) + "uniform sampler2D hs_range_map;\n" + std::string(shaders::lookup_light) +
            "float hs_transmittance(vec3 world_pos) { return 1.0; }\n";
        return make_entry(light, space, no_hair, [space](GLuint prog) { set_lookup_frustum(lookup_binder::for_pass(prog, 0), space); }, bias);
    }

    /// The lights' passes; without lights, one of a black light, for the ambient terms.
    const std::vector<light_entry>& passes() const {
        if (!lights_.empty()) return lights_;
        if (ambient_only_.empty()) {
            const scene_light dark{light_spec::directional({0.0f, 0.0f, -1.0f}), glm::vec3(0.0f)};
            ambient_only_.push_back(unshadowed_entry(dark, light_space::fit(dark.spec, aabb{glm::vec3(0.0f), glm::vec3(1.0f)}, 1), default_mesh_bias));
        }
        return ambient_only_;
    }

    /// The mesh's linear depth from `space`, nearest by MIN blending into R32F.
    /// Leaves the bound framebuffer and the viewport as it found them (draw() may make its light here).
    texture draw_mesh_depth(const light_space& space) const {
        const caller_errors_kept kept; // the caller's unread errors stay theirs, and fail nothing here
        GLint bound = 0, viewport[4] = {0, 0, 0, 0};
        glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &bound);
        glGetIntegerv(GL_VIEWPORT, viewport);
        const int res = space.resolution();
        auto [map, fbo] = linear_target(res, res, GL_R32F);
        const GLenum first = GL_COLOR_ATTACHMENT0;
        glDrawBuffers(1, &first);
        glViewport(0, 0, res, res);
        const float far_away[4] = {3.0e38f, 0, 0, 0};
        glClearBufferfv(GL_COLOR, 0, far_away);
        glDisable(GL_DEPTH_TEST);
        glEnable(GL_BLEND);
        glBlendEquation(GL_MIN);
        glUseProgram(depth_program_.get());
        set_light_uniforms(depth_program_.get(), space, raster_options{});
        draw_elements(mesh_, GL_TRIANGLES, mesh_count_);
        glBlendEquation(GL_FUNC_ADD);
        glDisable(GL_BLEND);
        glBindFramebuffer(GL_FRAMEBUFFER, GLuint(bound));
        glViewport(viewport[0], viewport[1], viewport[2], viewport[3]);
        check("mesh depth map");
        return std::move(map);
    }

    /// Clears the bound framebuffer (colour attachment 0 and depth) to the background and draws the scene.
    void clear_and_draw(const camera& cam, bool with_hair) const {
        const GLenum first = GL_COLOR_ATTACHMENT0;
        glDrawBuffers(1, &first);
        if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) throw gl_error("scene renderer: incomplete framebuffer");
        glViewport(0, 0, cam.width, cam.height);
        const float background[4] = {scene_.background.r, scene_.background.g, scene_.background.b, 1.0f};
        glClearBufferfv(GL_COLOR, 0, background);
        glClear(GL_DEPTH_BUFFER_BIT);
        draw(cam, with_hair);
    }

    /// Transparent hair: the mesh single-sampled and its 1/w, the hair's colours at its points, then
    /// gl::transparent_hair's passes into `target`.
    void render_transparent_into(const camera& cam, GLuint target) const {
        if (!inv_w_program_) {
            const auto vs = compile_stage(GL_VERTEX_SHADER, {}, {shaders::render_mesh_vertex}, "render/mesh_vertex");
            const auto fs = compile_stage(GL_FRAGMENT_SHADER, {}, {shaders::render_mesh_inv_w}, "render/mesh_inv_w");
            inv_w_program_ = link_program({&vs, &fs}, "mesh 1/w");
        }
        if (!transparent_) transparent_ = std::make_unique<transparent_hair>();
        const auto [base, base_fbo] = linear_target(cam.width, cam.height);
        auto depth = make_renderbuffer();
        glBindRenderbuffer(GL_RENDERBUFFER, depth.get());
        glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT32F, cam.width, cam.height);
        glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depth.get());
        clear_and_draw(cam, false);
        const auto colours = hair_colours(cam); // drawn with base_fbo bound: nothing is rasterised

        const auto [inv_w, inv_w_fbo] = linear_target(cam.width, cam.height, GL_R32F);
        const float none[4] = {0, 0, 0, 0};
        glClearBufferfv(GL_COLOR, 0, none);
        glDisable(GL_DEPTH_TEST);
        glEnable(GL_BLEND);
        glBlendEquation(GL_MAX);
        glUseProgram(inv_w_program_.get());
        const auto vp = cam.view_projection();
        glUniformMatrix4fv(glGetUniformLocation(inv_w_program_.get(), "hs_camera_view_projection"), 1, GL_FALSE, &vp[0][0]);
        draw_elements(mesh_, GL_TRIANGLES, mesh_count_);
        glBlendEquation(GL_FUNC_ADD);
        glDisable(GL_BLEND);

        const camera_hair hair{[this] { draw_elements(hair_, GL_LINES, hair_count_); },
                               colours.get(),
                               int(lights_.size()),
                               int(scene_.hair.point_count()),
                               scene_.material.ambient * scene_.material.colour,
                               inv_w.get(),
                               base.get()};
        peeled_layers_ = transparent_->blend(transparency_, hair, cam, hair_opacity_, line_width_, target);
        glBindFramebuffer(GL_FRAMEBUFFER, 0);
    }

    /// Each light's radiance of each hair point towards `cam`, in a shader storage buffer: light k's
    /// of point i at vec4 k * points + i (render/hair_colour); the ambient term is the blend's.
    buffer hair_colours(const camera& cam) const {
        const caller_errors_kept kept; // the caller's unread errors stay theirs, and fail nothing here
        const std::size_t points = scene_.hair.point_count();
        if (points > std::size_t(std::numeric_limits<GLsizei>::max()) || lights_.size() * points > std::size_t(std::numeric_limits<GLint>::max()))
            throw argument_error("too many hair points for one GL draw");
        for (const auto& l : lights_) // compiled before any state changes
            if (!l.colour_program) {
                const auto vs = compile_stage(GL_VERTEX_SHADER, {}, {l.lookup, shaders::render_light, shaders::render_hair_shading, shaders::render_hair_colour},
                                               "render/hair_colour");
                l.colour_program = link_program({&vs}, "hair colours");
            }
        auto colours = make_buffer();
        glBindBuffer(GL_SHADER_STORAGE_BUFFER, colours.get());
        glBufferData(GL_SHADER_STORAGE_BUFFER, GLsizeiptr(std::max<std::size_t>(1, lights_.size() * points) * sizeof(glm::vec4)), nullptr, GL_DYNAMIC_COPY);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, colours.get());
        glEnable(GL_RASTERIZER_DISCARD);
        for (std::size_t k = 0; k < lights_.size(); ++k) {
            const GLuint prog = lights_[k].colour_program.get();
            glUseProgram(prog);
            set_pass_uniforms(prog, lights_[k], cam, false); // the ambient term is added once, by the blend
            glUniform1i(glGetUniformLocation(prog, "hs_light_index"), GLint(k));
            glUniform1i(glGetUniformLocation(prog, "hs_point_count"), GLint(points));
            glBindVertexArray(hair_.vao.get());
            glDrawArrays(GL_POINTS, 0, GLsizei(points));
            glBindVertexArray(0);
        }
        glDisable(GL_RASTERIZER_DISCARD);
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT); // the blend's vertex stage reads them
        check("hair colours");
        return colours;
    }

    void set_pass_uniforms(GLuint prog, const light_entry& l, const camera& cam, bool first) const {
        l.bind_lookup(prog); // texture units from 0: as many as the method's look-up reads (up to 5)
        glActiveTexture(GLenum(GL_TEXTURE0 + mesh_depth_unit));
        glBindTexture(GL_TEXTURE_2D, l.mesh_depth.get());
        glUniform1i(glGetUniformLocation(prog, "hs_mesh_depth"), mesh_depth_unit);
        glActiveTexture(GL_TEXTURE0);
        glUniform1f(glGetUniformLocation(prog, "hs_mesh_bias"), l.mesh_bias);
        const auto vp = cam.view_projection();
        glUniformMatrix4fv(glGetUniformLocation(prog, "hs_camera_view_projection"), 1, GL_FALSE, &vp[0][0]);
        glUniform3fv(glGetUniformLocation(prog, "hs_eye"), 1, &cam.eye[0]);
        glUniform3fv(glGetUniformLocation(prog, "hs_light_colour"), 1, &l.light.colour[0]);
        glUniform3fv(glGetUniformLocation(prog, "hs_light_position"), 1, &l.light.spec.position[0]);
        glUniform3fv(glGetUniformLocation(prog, "hs_light_direction"), 1, &l.light.spec.direction[0]);
        glUniform1i(glGetUniformLocation(prog, "hs_light_directional"), l.light.spec.type == light_type::directional);
        glUniform1f(glGetUniformLocation(prog, "hs_light_cos_cone"),
                    l.light.spec.type == light_type::spot ? std::cos(glm::radians(l.light.spec.spot_half_angle_degrees)) : -2.0f);
        glUniform1f(glGetUniformLocation(prog, "hs_ambient_weight"), first ? 1.0f : 0.0f);
        const auto& m = scene_.material;
        glUniform3fv(glGetUniformLocation(prog, "hs_hair_colour"), 1, &m.colour[0]);
        glUniform3fv(glGetUniformLocation(prog, "hs_hair_specular"), 1, &m.specular_colour[0]);
        glUniform1f(glGetUniformLocation(prog, "hs_hair_shininess"), m.shininess);
        glUniform1f(glGetUniformLocation(prog, "hs_hair_ambient"), m.ambient);
        glUniform3fv(glGetUniformLocation(prog, "hs_mesh_colour"), 1, &scene_.mesh_colour[0]);
        glUniform1f(glGetUniformLocation(prog, "hs_mesh_ambient"), scene_.mesh_ambient);
    }

    const scene& scene_;
    geometry hair_, mesh_;
    std::size_t hair_floats_ = 0;
    GLsizei hair_count_ = 0, mesh_count_ = 0;
    program depth_program_, present_program_;
    mutable program inv_w_program_;
    transparency transparency_ = transparency::none;
    float hair_opacity_ = 0.4f, line_width_ = 1.0f;
    mutable std::unique_ptr<transparent_hair> transparent_;
    mutable int peeled_layers_ = 0;
    vertex_array empty_vao_ = make_vertex_array();
    std::vector<light_entry> lights_;
    mutable std::vector<light_entry> ambient_only_;
};

} // namespace hairshadow::gl
