#include "ImageDecoder.h"

#include <csetjmp>
#include <cstdio>
#include <cstring>

#include <jpeglib.h>
#include <stb_image.h>

namespace throng::gltf {
namespace {

bool isPng(const std::vector<std::uint8_t>& b) {
    static const std::uint8_t magic[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
    return b.size() >= 8 && std::memcmp(b.data(), magic, 8) == 0;
}
bool isJpeg(const std::vector<std::uint8_t>& b) { return b.size() >= 3 && b[0] == 0xFF && b[1] == 0xD8 && b[2] == 0xFF; }

// libjpeg reports fatal errors through error_exit, which must not return: jump back instead.
struct JpegError {
    jpeg_error_mgr mgr;
    std::jmp_buf jump;
    char message[JMSG_LENGTH_MAX];
};

void jpegFail(j_common_ptr info) {
    auto* e = reinterpret_cast<JpegError*>(info->err);
    info->err->format_message(info, e->message);
    std::longjmp(e->jump, 1);
}
void jpegQuiet(j_common_ptr, int) {}  // warnings (corrupt but decodable data) are not printed

// Decodes with libjpeg-turbo into `out` (already named). Only plain C data lives across setjmp.
bool decodeJpeg(const std::vector<std::uint8_t>& bytes, std::uint64_t maxPixels, Image& out, std::string& problem) {
    jpeg_decompress_struct info;
    JpegError err;
    info.err = jpeg_std_error(&err.mgr);
    err.mgr.error_exit = jpegFail;
    err.mgr.emit_message = jpegQuiet;
    err.message[0] = 0;
    std::uint8_t* volatile pixels = nullptr;  // malloc'd, volatile: read after longjmp
    std::uint8_t* volatile row = nullptr;
    if (setjmp(err.jump)) {
        jpeg_destroy_decompress(&info);
        std::free(pixels);
        std::free(row);
        problem = std::string("JPEG: ") + err.message;
        return false;
    }
    jpeg_create_decompress(&info);
    jpeg_mem_src(&info, bytes.data(), static_cast<unsigned long>(bytes.size()));
    jpeg_read_header(&info, TRUE);
    info.out_color_space = JCS_RGB;
    jpeg_start_decompress(&info);
    const std::uint64_t w = info.output_width, h = info.output_height;
    if (w == 0 || h == 0 || w * h > maxPixels || info.output_components != 3) {
        jpeg_destroy_decompress(&info);
        problem = "JPEG of " + std::to_string(w) + " x " + std::to_string(h) + " pixels exceeds the limit or is empty";
        return false;
    }
    pixels = static_cast<std::uint8_t*>(std::malloc(static_cast<std::size_t>(w * h * 4)));
    row = static_cast<std::uint8_t*>(std::malloc(static_cast<std::size_t>(w * 3)));
    if (!pixels || !row) {
        jpeg_destroy_decompress(&info);
        std::free(pixels);
        std::free(row);
        problem = "out of memory";
        return false;
    }
    while (info.output_scanline < info.output_height) {
        const std::uint64_t y = info.output_scanline;
        JSAMPROW rows[1] = {row};
        jpeg_read_scanlines(&info, rows, 1);
        for (std::uint64_t x = 0; x < w; ++x) {
            std::uint8_t* p = pixels + (y * w + x) * 4;
            p[0] = row[x * 3], p[1] = row[x * 3 + 1], p[2] = row[x * 3 + 2], p[3] = 255;
        }
    }
    jpeg_finish_decompress(&info);
    jpeg_destroy_decompress(&info);
    out.width = static_cast<int>(w);
    out.height = static_cast<int>(h);
    out.rgba.assign(pixels, pixels + w * h * 4);
    std::free(pixels);
    std::free(row);
    return true;
}

}  // namespace

std::optional<Image> decodeImage(const std::vector<std::uint8_t>& bytes, const std::string& name, std::uint64_t maxPixels,
                                 std::string& problem) {
    Image image;
    image.name = name;
    if (bytes.size() > static_cast<std::size_t>(INT32_MAX)) {
        problem = "image data too large";
        return std::nullopt;
    }
    if (isPng(bytes)) {
        const auto size = static_cast<int>(bytes.size());
        int w = 0, h = 0, c = 0;
        if (!stbi_info_from_memory(bytes.data(), size, &w, &h, &c) || w <= 0 || h <= 0) {
            problem = "PNG header cannot be read";
            return std::nullopt;
        }
        if (std::uint64_t(w) * std::uint64_t(h) > maxPixels) {
            problem = "PNG of " + std::to_string(w) + " x " + std::to_string(h) + " pixels exceeds the limit";
            return std::nullopt;
        }
        stbi_uc* data = stbi_load_from_memory(bytes.data(), size, &w, &h, &c, 4);
        if (!data) {
            problem = std::string("PNG: ") + (stbi_failure_reason() ? stbi_failure_reason() : "cannot decode");
            return std::nullopt;
        }
        image.width = w;
        image.height = h;
        image.rgba.assign(data, data + std::size_t(w) * std::size_t(h) * 4);
        stbi_image_free(data);
        return image;
    }
    if (isJpeg(bytes)) {
        if (!decodeJpeg(bytes, maxPixels, image, problem)) return std::nullopt;
        return image;
    }
    problem = "not a PNG or JPEG image";
    return std::nullopt;
}

}  // namespace throng::gltf
