#include "examples/peer/gl_frame.h"

// libOSMesa exports the GL entry points itself, so the prototypes are linked against it.
#define GL_GLEXT_PROTOTYPES 1
#include <GL/gl.h>
#include <GL/glext.h>

#include <glm/gtc/type_ptr.hpp>

#include <limits>
#include <string>

#include "examples/peer/peer_shaders.h"
#include "raster/pipeline/sample_pattern.h"
#include "raster/core/error.h"

namespace tessera::peer {
namespace {

std::string shader_log(GLuint object, bool is_program) {
    GLint length = 0;
    is_program ? glGetProgramiv(object, GL_INFO_LOG_LENGTH, &length)
               : glGetShaderiv(object, GL_INFO_LOG_LENGTH, &length);
    std::string log(size_t(length > 1 ? length : 1), '\0');
    is_program ? glGetProgramInfoLog(object, length, nullptr, log.data())
               : glGetShaderInfoLog(object, length, nullptr, log.data());
    for (char& c : log)
        if (c == '\n') c = ' ';
    return log.c_str();
}

GLuint compile(GLenum stage, const std::string& source) {
    const GLuint shader = glCreateShader(stage);
    const char* text = source.c_str();
    glShaderSource(shader, 1, &text, nullptr);
    glCompileShader(shader);
    GLint ok = 0;
    glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        const std::string log = shader_log(shader, false);
        glDeleteShader(shader);
        throw Error("llvmpipe: shader does not compile: " + log);
    }
    return shader;
}

std::string fragment_defines(const FrameOptions& options) {
    std::string defines;
    switch (options.shade) {
        case shade::ShadeMode::id: defines = "#define SHADE_ID\n"; break;
        case shade::ShadeMode::depth: defines = "#define SHADE_DEPTH\n"; break;
        case shade::ShadeMode::normal: defines = "#define SHADE_NORMAL\n"; break;
        case shade::ShadeMode::phong: defines = "#define SHADE_PHONG\n"; break;
    }
    if (options.triangle_ids) defines += "#define WRITE_ID\n";
    return defines;
}

GLuint link_program(const std::string& vertex_source, const std::string& fragment_source) {
    const std::string version = "#version 330 core\n";
    const GLuint vertex = compile(GL_VERTEX_SHADER, version + vertex_source);
    const GLuint fragment = compile(GL_FRAGMENT_SHADER, version + fragment_source);
    const GLuint program = glCreateProgram();
    glAttachShader(program, vertex);
    glAttachShader(program, fragment);
    glLinkProgram(program);
    glDeleteShader(vertex);
    glDeleteShader(fragment);
    GLint ok = 0;
    glGetProgramiv(program, GL_LINK_STATUS, &ok);
    if (!ok) {
        const std::string log = shader_log(program, true);
        glDeleteProgram(program);
        throw Error("llvmpipe: shader program does not link: " + log);
    }
    return program;
}

// issue 3's light for --shade phong: with d = |lookat - eye|, fwd, right = fwd x up and
// up' = right x fwd, the point light sits at eye + right*0.4d + up'*0.5d + fwd*0.2d.
glm::vec3 phong_light_position(const Camera& camera) {
    const glm::vec3 to_target = camera.lookat - camera.eye;
    const float d = glm::length(to_target);
    const glm::vec3 fwd = to_target / d;
    const glm::vec3 right = glm::normalize(glm::cross(fwd, camera.up));
    const glm::vec3 up = glm::cross(right, fwd);
    return camera.eye + right * (0.4f * d) + up * (0.5f * d) + fwd * (0.2f * d);
}

// Face normals for meshes without normals (issue 3): each triangle gets its own three
// vertices, so gl_PrimitiveID still counts triangles in file order.
struct Unindexed {
    std::vector<glm::vec3> positions, normals;
    std::vector<glm::vec2> uvs;
};

Unindexed unindex_with_face_normals(const Mesh& mesh) {
    Unindexed out;
    out.positions.reserve(mesh.indices.size());
    out.normals.reserve(mesh.indices.size());
    if (!mesh.uvs.empty()) out.uvs.reserve(mesh.indices.size());
    for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
        const glm::vec3 a = mesh.positions[mesh.indices[t]];
        const glm::vec3 b = mesh.positions[mesh.indices[t + 1]];
        const glm::vec3 c = mesh.positions[mesh.indices[t + 2]];
        const glm::vec3 n = glm::cross(b - a, c - a);  // normalised per pixel by the shader
        for (int k = 0; k < 3; ++k) {
            out.positions.push_back(mesh.positions[mesh.indices[t + k]]);
            out.normals.push_back(n);
            if (!mesh.uvs.empty()) out.uvs.push_back(mesh.uvs[mesh.indices[t + k]]);
        }
    }
    return out;
}

template <class T>
void upload_attribute(GLuint buffer, GLuint location, const std::vector<T>& values) {
    glBindBuffer(GL_ARRAY_BUFFER, buffer);
    glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(values.size() * sizeof(T)), values.data(),
                 GL_STATIC_DRAW);
    glEnableVertexAttribArray(location);
    glVertexAttribPointer(location, GLint(sizeof(T) / sizeof(float)), GL_FLOAT, GL_FALSE, 0,
                          nullptr);
}

}  // namespace

GlFrame::GlFrame(const Mesh& mesh, const Camera& camera, const FrameOptions& options)
    : options_(options) {
    if (mesh.indices.size() > size_t(std::numeric_limits<GLsizei>::max()))
        throw Error("llvmpipe: " + std::to_string(mesh.triangle_count()) +
                    " triangles are more than one OpenGL draw call takes");
    program_ = link_program(kVertexShader, fragment_defines(options) + kFragmentShader);
    glUseProgram(program_);
    // Rows top to bottom, and tessera's fill rule. llvmpipe applies its rule in framebuffer
    // rows, including an edge for the triangle at the larger row (D3D's top-left rule when
    // row 0 is the top); for a GL framebuffer object with the lower-left origin row 0 is
    // window y = 0, and by negating clip-space y window y becomes tessera's top-down
    // y = (1 - y_ndc) / 2 * height. So row 0 is the top of the image, the readback needs no
    // flip, and both renderers apply the top-left rule in the same coordinates. (The upper-left
    // clip origin of glClipControl flips rows too, but Mesa then switches to the bottom-edge
    // rule, to keep GL's convention in GL's y-up window space.) The flip mirrors the winding,
    // hence GL_CW as the front face.
    const glm::mat4 flip_y = glm::scale(glm::mat4(1.0f), glm::vec3(1.0f, -1.0f, 1.0f));
    glUniformMatrix4fv(glGetUniformLocation(program_, "view_projection"), 1, GL_FALSE,
                       glm::value_ptr(flip_y * camera.view_projection()));
    glUniform3fv(glGetUniformLocation(program_, "eye"), 1, glm::value_ptr(camera.eye));
    const glm::vec3 light = phong_light_position(camera);
    glUniform3fv(glGetUniformLocation(program_, "light_position"), 1, glm::value_ptr(light));

    glGenVertexArrays(1, &vertex_array_);
    glBindVertexArray(vertex_array_);
    glGenBuffers(4, buffers_);
    indexed_ = !mesh.normals.empty();
    if (indexed_) {
        upload_attribute(buffers_[0], 0, mesh.positions);
        upload_attribute(buffers_[1], 1, mesh.normals);
        if (!mesh.uvs.empty()) upload_attribute(buffers_[2], 2, mesh.uvs);
        glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, buffers_[3]);
        glBufferData(GL_ELEMENT_ARRAY_BUFFER, GLsizeiptr(mesh.indices.size() * 4),
                     mesh.indices.data(), GL_STATIC_DRAW);
        element_count_ = int(mesh.triangle_count() * 3);
    } else {
        const Unindexed flat = unindex_with_face_normals(mesh);
        upload_attribute(buffers_[0], 0, flat.positions);
        upload_attribute(buffers_[1], 1, flat.normals);
        if (!flat.uvs.empty()) upload_attribute(buffers_[2], 2, flat.uvs);
        element_count_ = int(flat.positions.size());
    }
    if (mesh.uvs.empty()) glVertexAttrib2f(2, 0.0f, 0.0f);  // issue 3: missing uv is (0,0)

    glGenRenderbuffers(3, renderbuffers_);
    glGenFramebuffers(1, &framebuffer_);
    glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_);
    if (options.samples > 1) {
        make_multisample_targets();
    } else {
        const GLenum formats[3] = {GL_RGBA8, GL_R32UI, GL_DEPTH_COMPONENT32F};
        const GLenum attachments[3] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1,
                                       GL_DEPTH_ATTACHMENT};
        for (int i = 0; i < 3; ++i) {
            if (i == 1 && !options.triangle_ids) continue;
            glBindRenderbuffer(GL_RENDERBUFFER, renderbuffers_[i]);
            glRenderbufferStorage(GL_RENDERBUFFER, formats[i], options.width, options.height);
            glFramebufferRenderbuffer(GL_FRAMEBUFFER, attachments[i], GL_RENDERBUFFER,
                                      renderbuffers_[i]);
        }
    }
    const GLenum draw_buffers[2] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
    glDrawBuffers(options.triangle_ids ? 2 : 1, draw_buffers);
    if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
        throw Error("llvmpipe: cannot make a " + std::to_string(options.width) + "x" +
                    std::to_string(options.height) + " framebuffer (too large for llvmpipe?)");

    glViewport(0, 0, options.width, options.height);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glFrontFace(GL_CW);  // counter-clockwise in NDC, seen through the y flip of view_projection
    if (options.cull == pipeline::CullMode::none) {
        glDisable(GL_CULL_FACE);
    } else {
        glEnable(GL_CULL_FACE);
        glCullFace(options.cull == pipeline::CullMode::back ? GL_BACK : GL_FRONT);
    }
    if (glGetError() != GL_NO_ERROR) throw Error("llvmpipe: OpenGL set-up failed");
}

// Multisample colour and depth renderbuffers and a multisample id texture (a texture, so the
// copy pass can fetch its samples), refused unless llvmpipe gives exactly the count asked for;
// then the positions llvmpipe samples at, matched with tessera's pattern.
void GlFrame::make_multisample_targets() {
    const int samples = options_.samples;
    const std::string asked = "llvmpipe: --samples " + std::to_string(samples) + ": ";
    GLint max_samples = 0, max_integer_samples = 0;
    glGetIntegerv(GL_MAX_SAMPLES, &max_samples);
    glGetIntegerv(GL_MAX_INTEGER_SAMPLES, &max_integer_samples);
    if (samples > max_samples)
        throw Error(asked + "this llvmpipe multisamples at most " + std::to_string(max_samples) +
                    " samples (GL_MAX_SAMPLES)");
    if (options_.triangle_ids && samples > max_integer_samples)
        throw Error(asked + "this llvmpipe multisamples integer (id) targets at most " +
                    std::to_string(max_integer_samples) + " samples (GL_MAX_INTEGER_SAMPLES)");
    const auto check_count = [&](GLint given, const char* target) {
        if (glGetError() != GL_NO_ERROR)
            throw Error(asked + "cannot make a " + std::to_string(options_.width) + "x" +
                        std::to_string(options_.height) + " multisample " + target + " target");
        if (given != samples)
            throw Error(asked + "llvmpipe gives the " + target + " target " + std::to_string(given) +
                        " samples instead");
    };
    const GLenum formats[2] = {GL_RGBA8, GL_DEPTH_COMPONENT32F};
    const GLenum attachments[2] = {GL_COLOR_ATTACHMENT0, GL_DEPTH_ATTACHMENT};
    const char* names[2] = {"colour", "depth"};
    for (int i = 0; i < 2; ++i) {
        const GLuint renderbuffer = renderbuffers_[i == 0 ? 0 : 2];
        glBindRenderbuffer(GL_RENDERBUFFER, renderbuffer);
        glRenderbufferStorageMultisample(GL_RENDERBUFFER, samples, formats[i], options_.width,
                                         options_.height);
        GLint given = 0;
        glGetRenderbufferParameteriv(GL_RENDERBUFFER, GL_RENDERBUFFER_SAMPLES, &given);
        check_count(given, names[i]);
        glFramebufferRenderbuffer(GL_FRAMEBUFFER, attachments[i], GL_RENDERBUFFER, renderbuffer);
    }
    if (options_.triangle_ids) {
        // Fixed sample locations: the same positions in every pixel, and required beside
        // renderbuffers for the framebuffer to be complete.
        glGenTextures(1, &sample_texture_);
        glBindTexture(GL_TEXTURE_2D_MULTISAMPLE, sample_texture_);
        glTexImage2DMultisample(GL_TEXTURE_2D_MULTISAMPLE, samples, GL_R32UI, options_.width,
                                options_.height, GL_TRUE);
        GLint given = 0;
        glGetTexLevelParameteriv(GL_TEXTURE_2D_MULTISAMPLE, 0, GL_TEXTURE_SAMPLES, &given);
        check_count(given, "id");
        glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT1, GL_TEXTURE_2D_MULTISAMPLE,
                               sample_texture_, 0);

        copy_program_ = link_program(kCopySampleVertexShader, kCopySampleFragmentShader);
        glUseProgram(copy_program_);
        glUniform1i(glGetUniformLocation(copy_program_, "ids"), 0);
        glUseProgram(program_);
        glGenVertexArrays(1, &copy_vertex_array_);  // no attributes, but core profile draws need one
        glGenRenderbuffers(1, &copy_renderbuffer_);
        glBindRenderbuffer(GL_RENDERBUFFER, copy_renderbuffer_);
        glRenderbufferStorage(GL_RENDERBUFFER, GL_R32UI, options_.width, options_.height);
        glGenFramebuffers(1, &copy_framebuffer_);
        glBindFramebuffer(GL_FRAMEBUFFER, copy_framebuffer_);
        glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER,
                                  copy_renderbuffer_);
        if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
            throw Error("llvmpipe: cannot make the " + std::to_string(options_.width) + "x" +
                        std::to_string(options_.height) + " target the samples are copied into");
        glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_);
    }

    // GL_SAMPLE_POSITION of a framebuffer object is in framebuffer rows (only window-system
    // framebuffers are reported flipped), which are tessera's top-down rows here (see the y flip
    // above), so it compares directly with tessera's offsets from the pixel centre.
    const glm::vec2* tessera_positions = pipeline::sample_positions(samples);
    gl_positions_.resize(size_t(samples));
    for (int s = 0; s < samples; ++s)
        glGetMultisamplefv(GL_SAMPLE_POSITION, GLuint(s), &gl_positions_[size_t(s)].x);
    gl_sample_of_.assign(size_t(samples), -1);
    for (int s = 0; s < samples; ++s)
        for (int g = 0; g < samples; ++g)
            if (gl_positions_[size_t(g)] == tessera_positions[s] + glm::vec2(0.5f)) gl_sample_of_[size_t(s)] = g;
}

std::string GlFrame::sample_position_mismatch() const {
    const auto list = [](const glm::vec2* p, size_t n) {
        std::string text;
        for (size_t i = 0; i < n; ++i)
            text += (i ? " (" : "(") + std::to_string(p[i].x) + "," + std::to_string(p[i].y) + ")";
        return text;
    };
    for (int g : gl_sample_of_)
        if (g < 0) {
            std::vector<glm::vec2> tessera(size_t(options_.samples));
            for (size_t s = 0; s < tessera.size(); ++s)
                tessera[s] = pipeline::sample_positions(options_.samples)[s] + glm::vec2(0.5f);
            return "llvmpipe's " + std::to_string(options_.samples) + "-sample positions " +
                   list(gl_positions_.data(), gl_positions_.size()) + " are not tessera's " +
                   list(tessera.data(), tessera.size()) + ": their ids are not comparable sample for sample";
        }
    return {};
}

GlFrame::~GlFrame() {
    glDeleteFramebuffers(1, &copy_framebuffer_);
    glDeleteRenderbuffers(1, &copy_renderbuffer_);
    glDeleteVertexArrays(1, &copy_vertex_array_);
    glDeleteProgram(copy_program_);
    glDeleteTextures(1, &sample_texture_);
    glDeleteFramebuffers(1, &framebuffer_);
    glDeleteRenderbuffers(3, renderbuffers_);
    glDeleteBuffers(4, buffers_);
    glDeleteVertexArrays(1, &vertex_array_);
    glDeleteProgram(program_);
}

void GlFrame::render() {
    const GLfloat black[4] = {0.0f, 0.0f, 0.0f, 1.0f};
    const GLuint no_triangle[4] = {0, 0, 0, 0};
    const GLfloat far = 1.0f;
    glClearBufferfv(GL_COLOR, 0, black);
    if (options_.triangle_ids) glClearBufferuiv(GL_COLOR, 1, no_triangle);
    glClearBufferfv(GL_DEPTH, 0, &far);
    if (indexed_)
        glDrawElements(GL_TRIANGLES, element_count_, GL_UNSIGNED_INT, nullptr);
    else
        glDrawArrays(GL_TRIANGLES, 0, element_count_);
    glFinish();
}

template <class T>
std::vector<T> GlFrame::read(unsigned attachment, unsigned format, unsigned type,
                             int channels) const {
    std::vector<T> pixels(size_t(options_.width) * size_t(options_.height) * size_t(channels));
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    if (attachment != GL_DEPTH_ATTACHMENT) glReadBuffer(attachment);
    glReadPixels(0, 0, options_.width, options_.height, format, type, pixels.data());
    if (glGetError() != GL_NO_ERROR) throw Error("llvmpipe: reading the frame back failed");
    return pixels;
}

std::vector<uint8_t> GlFrame::colour_rgb8() const {
    return read<uint8_t>(GL_COLOR_ATTACHMENT0, GL_RGB, GL_UNSIGNED_BYTE, 3);
}

// One pass per sample: the copy program fetches sample gl_sample_of_[s] of every pixel into
// the single-sample target, which is read back into tessera's sample s.
VisibilityBuffer GlFrame::sample_ids() const {
    const int samples = options_.samples;
    VisibilityBuffer visibility;
    visibility.reset(options_.width, options_.height);
    visibility.samples = samples;
    visibility.sample_triangle.assign(visibility.triangle.size() * size_t(samples), kNoTriangle);
    glBindFramebuffer(GL_FRAMEBUFFER, copy_framebuffer_);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_CULL_FACE);
    glUseProgram(copy_program_);
    glBindVertexArray(copy_vertex_array_);
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D_MULTISAMPLE, sample_texture_);
    for (int s = 0; s < samples; ++s) {
        glUniform1i(glGetUniformLocation(copy_program_, "sample_index"), gl_sample_of_[size_t(s)]);
        glDrawArrays(GL_TRIANGLES, 0, 3);
        const std::vector<uint32_t> ids = read<uint32_t>(GL_COLOR_ATTACHMENT0, GL_RED_INTEGER, GL_UNSIGNED_INT, 1);
        for (size_t p = 0; p < ids.size(); ++p)
            visibility.sample_triangle[p * size_t(samples) + size_t(s)] = ids[p] - 1;  // 0 (empty) wraps to kNoTriangle
    }
    // Back to the frame's state, for the next render().
    glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_);
    glUseProgram(program_);
    glBindVertexArray(vertex_array_);
    glEnable(GL_DEPTH_TEST);
    if (options_.cull != pipeline::CullMode::none) glEnable(GL_CULL_FACE);
    return visibility;
}

VisibilityBuffer GlFrame::visibility() const {
    if (options_.samples > 1) {
        if (!options_.triangle_ids) throw Error("llvmpipe: a multisampled frame reads back its ids only");
        if (const std::string differ = sample_position_mismatch(); !differ.empty()) throw Error(differ);
        return sample_ids();
    }
    VisibilityBuffer visibility;
    visibility.reset(options_.width, options_.height);
    const std::vector<float> depth = read<float>(GL_DEPTH_ATTACHMENT, GL_DEPTH_COMPONENT, GL_FLOAT, 1);
    visibility.depth.assign(depth.begin(), depth.end());
    if (options_.triangle_ids) {
        const std::vector<uint32_t> ids =
            read<uint32_t>(GL_COLOR_ATTACHMENT1, GL_RED_INTEGER, GL_UNSIGNED_INT, 1);
        visibility.triangle.assign(ids.begin(), ids.end());
        for (uint32_t& id : visibility.triangle) id -= 1;  // 0 (cleared: empty) wraps to kNoTriangle
    }
    return visibility;
}

}  // namespace tessera::peer
