/// \file
/// \brief PNG output through libpng, written atomically (temporary file + rename).
#include "plot/image.hpp"

#include "plot/error.hpp"

#include <png.h>

#include <cerrno>
#include <csetjmp>
#include <cstdio>
#include <cstring>
#include <fcntl.h>
#include <filesystem>
#include <sys/stat.h>
#include <unistd.h>

namespace plot {

Image::Image(int width_, int height_, std::array<std::uint8_t, 3> fill)
    : width(width_), height(height_) {
    rgb.resize(static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * 3);
    for (std::size_t i = 0; i < rgb.size(); i += 3) {
        rgb[i] = fill[0];
        rgb[i + 1] = fill[1];
        rgb[i + 2] = fill[2];
    }
}

std::array<std::uint8_t, 3> Image::at(int x, int y) const {
    if (x < 0 || y < 0 || x >= width || y >= height)
        throw Error("pixel (" + std::to_string(x) + ", " + std::to_string(y) + ") is outside the " +
                    std::to_string(width) + "×" + std::to_string(height) + " image");
    const std::size_t i = (static_cast<std::size_t>(y) * width + x) * 3;
    return {rgb[i], rgb[i + 1], rgb[i + 2]};
}

namespace {

/// libpng reports errors through longjmp; this is where the message lands.
struct PngErrorSink {
    char message[256] = "";
};

void on_png_error(png_structp png, png_const_charp message) {
    auto* sink = static_cast<PngErrorSink*>(png_get_error_ptr(png));
    std::snprintf(sink->message, sizeof sink->message, "%s", message);
    png_longjmp(png, 1);
}

void on_png_warning(png_structp, png_const_charp) {}

/// Encodes the rows to \p file.  Plain C style on purpose: nothing with a destructor lives in
/// this frame, so libpng's longjmp on error is safe.  Returns false and fills \p sink on error.
bool encode_png(std::FILE* file, int width, int height, png_bytep* rows, PngErrorSink* sink) {
    png_structp png =
        png_create_write_struct(PNG_LIBPNG_VER_STRING, sink, on_png_error, on_png_warning);
    if (png == nullptr) {
        std::snprintf(sink->message, sizeof sink->message, "libpng could not start");
        return false;
    }
    png_infop info = png_create_info_struct(png);
    if (info == nullptr || setjmp(png_jmpbuf(png))) {
        png_destroy_write_struct(&png, &info);
        return false;
    }
    png_init_io(png, file);
    png_set_IHDR(png, info, static_cast<png_uint_32>(width), static_cast<png_uint_32>(height), 8,
                 PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT,
                 PNG_FILTER_TYPE_DEFAULT);
    png_set_sRGB(png, info, PNG_sRGB_INTENT_PERCEPTUAL);
    png_set_compression_level(png, 6);
    png_write_info(png, info);
    png_write_image(png, rows);
    png_write_end(png, info);
    png_destroy_write_struct(&png, &info);
    return true;
}

std::filesystem::path directory_of(const std::string& path) {
    std::filesystem::path dir = std::filesystem::path(path).parent_path();
    return dir.empty() ? std::filesystem::path(".") : dir;
}

/// Opens a fresh temporary file next to \p path (same directory, so rename is atomic).
std::pair<std::string, std::FILE*> open_temporary(const std::string& path) {
    for (int attempt = 0; attempt < 100; ++attempt) {
        const std::string name =
            path + ".tmp" + std::to_string(::getpid()) + "_" + std::to_string(attempt);
        const int fd = ::open(name.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
        if (fd >= 0) return {name, ::fdopen(fd, "wb")};
        if (errno != EEXIST)
            throw Error("cannot write PNG '" + path + "': " + std::strerror(errno));
    }
    throw Error("cannot write PNG '" + path + "': no free temporary file name");
}

}  // namespace

void check_writable(const std::string& path) {
    if (path.empty()) throw Error("cannot write PNG: the output path is empty");
    const std::filesystem::path dir = directory_of(path);
    std::error_code ec;
    if (!std::filesystem::is_directory(dir, ec))
        throw Error("cannot write PNG '" + path + "': directory '" + dir.string() +
                    "' does not exist");
    if (std::filesystem::is_directory(path, ec))
        throw Error("cannot write PNG '" + path + "': it is a directory");
    if (::access(dir.c_str(), W_OK) != 0)
        throw Error("cannot write PNG '" + path + "': directory '" + dir.string() +
                    "' is not writable");
}

void write_png(const Image& image, const std::string& path) {
    check_writable(path);
    if (image.width <= 0 || image.height <= 0 ||
        image.rgb.size() != static_cast<std::size_t>(image.width) * image.height * 3)
        throw Error("cannot write PNG '" + path + "': the image is empty or inconsistent");

    std::vector<png_bytep> rows(static_cast<std::size_t>(image.height));
    for (int y = 0; y < image.height; ++y)
        rows[y] =
            const_cast<png_bytep>(image.rgb.data() + static_cast<std::size_t>(y) * image.width * 3);

    auto [temporary, file] = open_temporary(path);
    if (file == nullptr) {
        ::unlink(temporary.c_str());
        throw Error("cannot write PNG '" + path + "': " + std::strerror(errno));
    }
    PngErrorSink sink;
    const bool encoded = encode_png(file, image.width, image.height, rows.data(), &sink);
    const bool flushed = std::fflush(file) == 0 && !std::ferror(file);
    const int saved_errno = errno;
    const bool closed = std::fclose(file) == 0;
    if (!encoded || !flushed || !closed) {
        ::unlink(temporary.c_str());
        throw Error("cannot write PNG '" + path +
                    "': " + (encoded ? std::string(std::strerror(saved_errno)) : sink.message));
    }
    if (std::rename(temporary.c_str(), path.c_str()) != 0) {
        const int rename_errno = errno;
        ::unlink(temporary.c_str());
        throw Error("cannot write PNG '" + path +
                    "': rename failed: " + std::strerror(rename_errno));
    }
}

}  // namespace plot
