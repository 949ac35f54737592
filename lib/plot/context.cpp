/// \file
/// \brief The OSMesa canvas: context, shaders, draw calls, downsampling.
///
/// Notes from TOOLCHAIN.md: define GL_GLEXT_PROTOTYPES and link OSMesa only (never libGL, or
/// glGetString returns NULL); the colour buffer is ours and bottom-up; llvmpipe's smooth points
/// and lines look poor, so we render at 2-3x and box-filter instead.
#define GL_GLEXT_PROTOTYPES 1
#include "plot/context.hpp"

#include "plot/error.hpp"

#include <GL/osmesa.h>
#include <GL/gl.h>
#include <GL/glext.h>

#include <algorithm>
#include <cmath>
#include <string>

namespace plot::detail {
namespace {

// ---- Shaders --------------------------------------------------------------------------------
// Positions arrive in final-image pixels (y down) and become clip coordinates here.
constexpr const char* vertex_source = R"(#version 130
in vec2 position;
in vec4 color;
in vec2 texcoord;
uniform vec2 viewport;
out vec4 v_color;
out vec2 v_texcoord;
void main() {
    gl_Position = vec4(2.0 * position.x / viewport.x - 1.0, 1.0 - 2.0 * position.y / viewport.y,
                       0.0, 1.0);
    v_color = color;
    v_texcoord = texcoord;
}
)";

constexpr const char* flat_fragment_source = R"(#version 130
in vec4 v_color;
void main() { gl_FragColor = v_color; }
)";

// Marker shapes on point sprites: each shape is a distance-like function d(p) that is 1 on the
// outline; open shapes keep only 1 - ring < d <= 1.  Plus and cross are bars of width ring.
constexpr const char* marker_fragment_source = R"(#version 130
in vec4 v_color;
uniform int shape;
uniform float ring;
void main() {
    vec2 p = 2.0 * gl_PointCoord - 1.0;
    p.y = -p.y;
    float d;
    if (shape == 1) {
        d = length(p);
    } else if (shape == 2) {
        d = max(abs(p.x), abs(p.y)) / 0.82;
    } else if (shape == 3) {
        vec2 q = vec2(p.x, p.y + 0.18);
        d = 2.0 * max(-q.y, max(0.866 * q.x + 0.5 * q.y, -0.866 * q.x + 0.5 * q.y)) / 0.98;
    } else if (shape == 4) {
        d = abs(p.x) + abs(p.y);
    } else {
        vec2 q = shape == 6 ? vec2(p.x + p.y, p.x - p.y) * 0.70710678 : p;
        float half_width = max(ring, 0.1) * 0.5;
        if (min(abs(q.x), abs(q.y)) > half_width || max(abs(q.x), abs(q.y)) > 1.0) discard;
        gl_FragColor = v_color;
        return;
    }
    if (d > 1.0) discard;
    if (ring > 0.0 && d < 1.0 - ring) discard;
    gl_FragColor = v_color;
}
)";

constexpr const char* texture_fragment_source = R"(#version 130
in vec2 v_texcoord;
uniform sampler2D image;
void main() { gl_FragColor = texture(image, v_texcoord); }
)";

constexpr GLuint position_location = 0;
constexpr GLuint color_location = 1;
constexpr GLuint texcoord_location = 2;

GLuint compile(GLenum type, const char* source) {
    const GLuint shader = glCreateShader(type);
    glShaderSource(shader, 1, &source, nullptr);
    glCompileShader(shader);
    GLint ok = 0;
    glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        char log[1024] = "";
        glGetShaderInfoLog(shader, sizeof log, nullptr, log);
        throw Error(std::string("GL shader does not compile: ") + log);
    }
    return shader;
}

GLuint link_program(const char* fragment_source) {
    const GLuint program = glCreateProgram();
    const GLuint vs = compile(GL_VERTEX_SHADER, vertex_source);
    const GLuint fs = compile(GL_FRAGMENT_SHADER, fragment_source);
    glAttachShader(program, vs);
    glAttachShader(program, fs);
    glBindAttribLocation(program, position_location, "position");
    glBindAttribLocation(program, color_location, "color");
    glBindAttribLocation(program, texcoord_location, "texcoord");
    glLinkProgram(program);
    glDeleteShader(vs);
    glDeleteShader(fs);
    GLint ok = 0;
    glGetProgramiv(program, GL_LINK_STATUS, &ok);
    if (!ok) {
        char log[1024] = "";
        glGetProgramInfoLog(program, sizeof log, nullptr, log);
        throw Error(std::string("GL program does not link: ") + log);
    }
    return program;
}

int marker_code(Marker m) {
    switch (m) {
        case Marker::none:
            return 0;
        case Marker::circle:
            return 1;
        case Marker::square:
            return 2;
        case Marker::triangle:
            return 3;
        case Marker::diamond:
            return 4;
        case Marker::plus:
            return 5;
        case Marker::cross:
            return 6;
    }
    return 1;
}

}  // namespace

struct Canvas::Impl {
    OSMesaContext context = nullptr;
    std::vector<std::uint8_t> buffer;  ///< RGBA, bottom row first
    GLuint flat = 0, marker = 0, textured = 0;
};

// ---- Set-up ---------------------------------------------------------------------------------
Canvas::Canvas(int width, int height, int supersample, const Color& background)
    : impl_(std::make_unique<Impl>()), width_(width), height_(height), supersample_(supersample) {
    const long w = static_cast<long>(width) * supersample,
               h = static_cast<long>(height) * supersample;
    if (width <= 0 || height <= 0 || supersample <= 0 || w > max_buffer_side || h > max_buffer_side)
        throw Error("OSMesa: cannot create a " + std::to_string(w) + "×" + std::to_string(h) +
                    " pixel GL buffer (the limit is " + std::to_string(max_buffer_side) +
                    " a side)");

    impl_->context = OSMesaCreateContextExt(OSMESA_RGBA, 0, 0, 0, nullptr);
    if (impl_->context == nullptr) throw Error("OSMesa: no off-screen GL context could be created");
    impl_->buffer.assign(static_cast<std::size_t>(w) * h * 4, 0);
    if (!OSMesaMakeCurrent(impl_->context, impl_->buffer.data(), GL_UNSIGNED_BYTE,
                           static_cast<GLsizei>(w), static_cast<GLsizei>(h))) {
        OSMesaDestroyContext(impl_->context);
        throw Error("OSMesa: the GL context cannot be made current on a " + std::to_string(w) +
                    "×" + std::to_string(h) + " buffer");
    }
    if (glGetString(GL_VERSION) == nullptr) {
        OSMesaDestroyContext(impl_->context);
        throw Error(
            "no GL context: glGetString returned NULL (is libGL linked instead of OSMesa?)");
    }

    impl_->flat = link_program(flat_fragment_source);
    impl_->marker = link_program(marker_fragment_source);
    impl_->textured = link_program(texture_fragment_source);
    for (GLuint program : {impl_->flat, impl_->marker, impl_->textured}) {
        glUseProgram(program);
        glUniform2f(glGetUniformLocation(program, "viewport"), static_cast<float>(width),
                    static_cast<float>(height));
    }

    glViewport(0, 0, static_cast<GLsizei>(w), static_cast<GLsizei>(h));
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_DITHER);
    glEnable(GL_BLEND);
    glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
    glEnable(GL_POINT_SPRITE);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glClearColor(static_cast<float>(background.r), static_cast<float>(background.g),
                 static_cast<float>(background.b), 1.0f);
    glClear(GL_COLOR_BUFFER_BIT);
}

Canvas::~Canvas() {
    glDeleteProgram(impl_->flat);
    glDeleteProgram(impl_->marker);
    glDeleteProgram(impl_->textured);
    OSMesaDestroyContext(impl_->context);
}

// ---- Clipping -------------------------------------------------------------------------------
void Canvas::clip(const Rect& r) {
    // Scissor boxes are in buffer pixels, bottom-up; round outwards to whole final pixels.
    const int s = supersample_;
    const int x0 = static_cast<int>(std::floor(r.x0)) * s,
              x1 = static_cast<int>(std::ceil(r.x1)) * s;
    const int y0 = (height_ - static_cast<int>(std::ceil(r.y1))) * s;
    const int y1 = (height_ - static_cast<int>(std::floor(r.y0))) * s;
    glEnable(GL_SCISSOR_TEST);
    glScissor(x0, y0, std::max(0, x1 - x0), std::max(0, y1 - y0));
}

void Canvas::unclip() { glDisable(GL_SCISSOR_TEST); }

// ---- Drawing --------------------------------------------------------------------------------
namespace {

/// Sets one colour for every vertex, quantised to 8 bits first so that GL stores exactly the
/// bytes plot::to_rgb8 gives (GL's own float -> byte rounding may differ by one).
void set_constant_color(const Color& c, double alpha) {
    const auto rgb = to_rgb8(c);
    glDisableVertexAttribArray(color_location);
    glVertexAttrib4f(color_location, rgb[0] / 255.0f, rgb[1] / 255.0f, rgb[2] / 255.0f,
                     static_cast<float>(alpha));
}

void set_positions(std::span<const float> xy) {
    glBindBuffer(GL_ARRAY_BUFFER, 0);
    glEnableVertexAttribArray(position_location);
    glVertexAttribPointer(position_location, 2, GL_FLOAT, GL_FALSE, 0, xy.data());
}

}  // namespace

void Canvas::triangles(std::span<const float> xy, const Color& color, double alpha) {
    if (xy.size() < 6) return;
    glUseProgram(impl_->flat);
    set_positions(xy);
    set_constant_color(color, alpha);
    glDrawArrays(GL_TRIANGLES, 0, static_cast<GLsizei>(xy.size() / 2));
}

void Canvas::rect(const Rect& r, const Color& color, double alpha) {
    const float x0 = static_cast<float>(r.x0), x1 = static_cast<float>(r.x1);
    const float y0 = static_cast<float>(r.y0), y1 = static_cast<float>(r.y1);
    const float xy[] = {x0, y0, x1, y0, x1, y1, x0, y0, x1, y1, x0, y1};
    triangles(xy, color, alpha);
}

void Canvas::markers(std::span<const float> xy, double size, Marker shape, double outline,
                     const Color& color, double alpha, std::span<const std::uint8_t> rgba) {
    if (xy.size() < 2 || shape == Marker::none) return;
    glUseProgram(impl_->marker);
    set_positions(xy);
    if (rgba.size() >= xy.size() * 2) {
        glEnableVertexAttribArray(color_location);
        glVertexAttribPointer(color_location, 4, GL_UNSIGNED_BYTE, GL_TRUE, 0, rgba.data());
    } else {
        set_constant_color(color, alpha);
    }
    // The sprite size is limited to 255 buffer pixels by llvmpipe.
    const double sprite = std::min(255.0, size * supersample_);
    // Plus and cross are always strokes, at least a pixel and 15 % of the size wide.
    const bool bar = shape == Marker::plus || shape == Marker::cross;
    const double stroke = bar ? std::max(outline, std::max(1.0, 0.15 * size)) : outline;
    glUniform1i(glGetUniformLocation(impl_->marker, "shape"), marker_code(shape));
    glUniform1f(glGetUniformLocation(impl_->marker, "ring"),
                static_cast<float>(2.0 * stroke / size));
    glPointSize(static_cast<float>(sprite));
    glDrawArrays(GL_POINTS, 0, static_cast<GLsizei>(xy.size() / 2));
    glDisableVertexAttribArray(color_location);
}

void Canvas::texture(std::span<const std::uint8_t> rgba, int tex_width, int tex_height,
                     const Rect& where) {
    GLuint name = 0;
    glGenTextures(1, &name);
    glBindTexture(GL_TEXTURE_2D, name);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, tex_width, tex_height, 0, GL_RGBA, GL_UNSIGNED_BYTE,
                 rgba.data());

    glUseProgram(impl_->textured);
    glUniform1i(glGetUniformLocation(impl_->textured, "image"), 0);
    const float x0 = static_cast<float>(where.x0), x1 = static_cast<float>(where.x1);
    const float top = static_cast<float>(where.y0), bottom = static_cast<float>(where.y1);
    // Texture row 0 is the lowest row of the image: t = 0 at the bottom edge.
    const float xy[] = {x0, bottom, x1, bottom, x1, top, x0, bottom, x1, top, x0, top};
    const float uv[] = {0, 0, 1, 0, 1, 1, 0, 0, 1, 1, 0, 1};
    set_positions(xy);
    set_constant_color(white, 1.0);
    glEnableVertexAttribArray(texcoord_location);
    glVertexAttribPointer(texcoord_location, 2, GL_FLOAT, GL_FALSE, 0, uv);
    glDrawArrays(GL_TRIANGLES, 0, 6);
    glDisableVertexAttribArray(texcoord_location);
    glDeleteTextures(1, &name);
}

// ---- Resolve --------------------------------------------------------------------------------
Image Canvas::resolve() {
    glFinish();
    const int s = supersample_;
    const std::size_t buffer_width = static_cast<std::size_t>(width_) * s;
    const unsigned samples = static_cast<unsigned>(s * s);
    Image image(width_, height_);
    // Rows are independent; integer sums keep the result the same for any thread count.
#pragma omp parallel for schedule(static)
    for (int y = 0; y < height_; ++y) {
        // Final row y (top-down) is buffer rows (height - 1 - y) * s ... + s - 1 (bottom-up).
        const std::size_t first_row = static_cast<std::size_t>(height_ - 1 - y) * s;
        for (int x = 0; x < width_; ++x) {
            unsigned sum[3] = {0, 0, 0};
            for (int dy = 0; dy < s; ++dy) {
                const std::uint8_t* p = &impl_->buffer[((first_row + dy) * buffer_width +
                                                        static_cast<std::size_t>(x) * s) *
                                                       4];
                for (int dx = 0; dx < s; ++dx, p += 4) {
                    sum[0] += p[0];
                    sum[1] += p[1];
                    sum[2] += p[2];
                }
            }
            std::uint8_t* out = &image.rgb[(static_cast<std::size_t>(y) * width_ + x) * 3];
            for (int c = 0; c < 3; ++c)
                out[c] = static_cast<std::uint8_t>((sum[c] + samples / 2) / samples);
        }
    }
    return image;
}

}  // namespace plot::detail
