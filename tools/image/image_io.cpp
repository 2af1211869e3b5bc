// image_io.cpp - the C interface of image_io.h over OpenImageIO (files) and OpenColorIO
// (scene-linear <-> display). Nothing here encodes pixels or colour by hand: files are
// encoded (in memory, through OpenImageIO's IOVecOutput proxy) and read by OpenImageIO,
// display transforms are OpenColorIO processors, and the false-colour map is OpenImageIO's
// ImageBufAlgo::color_map. Writing the encoded bytes to disk is the caller's (out_file.h).
#include "image_io.h"

#include <OpenColorIO/OpenColorIO.h>
#include <OpenEXR/openexr.h>
#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imagebufalgo.h>
#include <OpenImageIO/imageio.h>
#include <sys/stat.h>

#include <algorithm>
#include <memory>
#include <new>
#include <cctype>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <string>
#include <vector>

namespace OCIO = OCIO_NAMESPACE;
namespace OIIO = OIIO_NAMESPACE;

namespace
{

// Largest image accepted, in pixels: keeps width*height*3 floats far from size_t overflow
// and a corrupt header from asking for an absurd allocation.
const long long kMaxPixels = 1LL << 28;
// Largest read, in bytes: the pixels of the channels used (RGB or grey) as 32-bit floats.
const long long kMaxReadBytes = 1LL << 30;
// Rows read at a time: what is allocated grows with what the file really holds, so a header
// that declares a huge image over a few bytes fails at its first missing rows.
const int kStripRows = 64;

void set_err(char *err, int err_size, const std::string &msg)
{
    if (err && err_size > 0) std::snprintf(err, (size_t)err_size, "%s", msg.c_str());
}

// Is byte c the continuation of a UTF-8 sequence (no cut before it)?
bool continuation(char c) { return ((unsigned char)c & 0xc0) == 0x80; }

// "PATH: reason" into err; if it does not fit, the path is shortened in its middle, never the
// reason; its control bytes are shown as \xHH (as path_msg.h does for the C tools).
void set_err_path(char *err, int err_size, const char *path, const std::string &reason)
{
    std::string p, r = ": " + (reason.empty() ? std::string("failed") : reason);
    for (const char *c = path ? path : ""; *c; ++c) {
        char hex[8];
        if ((unsigned char)*c < 0x20 || *c == 0x7f) {
            std::snprintf(hex, sizeof hex, "\\x%02x", (unsigned char)*c);
            p += hex;
        } else {
            p += *c;
        }
    }
    if (err_size > 0 && p.size() + r.size() >= (size_t)err_size) {
        size_t room = (size_t)err_size - 1 > r.size() + 16 ? (size_t)err_size - 1 - r.size() : 16;
        if (p.size() > room) {
            size_t head = (room - 3) / 3, from = p.size() - (room - 3 - head);
            while (head > 0 && continuation(p[head])) --head;
            while (from < p.size() && continuation(p[from])) ++from;
            p = p.substr(0, head) + "..." + p.substr(from);
        }
    }
    set_err(err, err_size, p + r);
}

std::string lower_ext(const char *path)
{
    std::string p(path), ext;
    size_t dot = p.find_last_of('.'), slash = p.find_last_of('/');
    if (dot != std::string::npos && (slash == std::string::npos || dot > slash))
        ext = p.substr(dot + 1);
    for (char &c : ext) c = (char)std::tolower((unsigned char)c);
    return ext;
}

// Names used by the built-in configuration (see builtin_config).
const char *const kSceneLinear = "Linear Rec.709 (sRGB)";
const char *const kDisplay = "sRGB";
const char *const kView = "Standard";

// OpenColorIO 2.1 has no built-in ocio:// configs, so the default configuration is assembled
// here from OpenColorIO's own built-in transforms, following the structure of the ACES
// "CG" studio config: scene reference ACEScg, display reference CIE XYZ (D65), one display
// "sRGB" (piecewise sRGB EOTF) with the view "Standard" (no tone mapping). Linear Rec.709
// with sRGB primaries is the scene_linear role, which is what the renderer writes.
OCIO::ConstConfigRcPtr builtin_config()
{
    OCIO::ConfigRcPtr cfg = OCIO::Config::CreateRaw()->createEditableCopy();
    cfg->setName("abrdf-builtin-srgb");
    cfg->setDescription(
        "sRGB display for scene-linear Rec.709, from OpenColorIO built-in transforms");
    // CreateRaw brings one "raw" colour space, a "raw" view and a "Raw" display; start clean.
    cfg->clearColorSpaces();
    cfg->clearDisplays();
    cfg->clearViewTransforms();

    OCIO::ColorSpaceRcPtr acescg = OCIO::ColorSpace::Create(OCIO::REFERENCE_SPACE_SCENE);
    acescg->setName("ACEScg");
    cfg->addColorSpace(acescg);

    OCIO::ColorSpaceRcPtr lin709 = OCIO::ColorSpace::Create(OCIO::REFERENCE_SPACE_SCENE);
    lin709->setName(kSceneLinear);
    OCIO::BuiltinTransformRcPtr ap1_to_709 = OCIO::BuiltinTransform::Create();
    ap1_to_709->setStyle("UTILITY - ACES-AP1_to_LINEAR-REC709_BFD");
    lin709->setTransform(ap1_to_709, OCIO::COLORSPACE_DIR_FROM_REFERENCE);
    cfg->addColorSpace(lin709);

    OCIO::ColorSpaceRcPtr xyz = OCIO::ColorSpace::Create(OCIO::REFERENCE_SPACE_DISPLAY);
    xyz->setName("CIE-XYZ-D65");
    cfg->addColorSpace(xyz);

    OCIO::ColorSpaceRcPtr srgb = OCIO::ColorSpace::Create(OCIO::REFERENCE_SPACE_DISPLAY);
    srgb->setName("sRGB - Display");
    OCIO::BuiltinTransformRcPtr to_srgb = OCIO::BuiltinTransform::Create();
    to_srgb->setStyle("DISPLAY - CIE-XYZ-D65_to_sRGB");
    srgb->setTransform(to_srgb, OCIO::COLORSPACE_DIR_FROM_REFERENCE);
    cfg->addColorSpace(srgb);

    OCIO::ViewTransformRcPtr untone = OCIO::ViewTransform::Create(OCIO::REFERENCE_SPACE_SCENE);
    untone->setName("Un-tone-mapped");
    OCIO::BuiltinTransformRcPtr ap1_to_xyz = OCIO::BuiltinTransform::Create();
    ap1_to_xyz->setStyle("UTILITY - ACES-AP1_to_CIE-XYZ-D65_BFD");
    untone->setTransform(ap1_to_xyz, OCIO::VIEWTRANSFORM_DIR_FROM_REFERENCE);
    cfg->addViewTransform(untone);

    cfg->addDisplayView(kDisplay, kView, "Un-tone-mapped", "sRGB - Display", "", "", "");
    cfg->setActiveDisplays(kDisplay);
    cfg->setActiveViews(kView);
    cfg->setRole(OCIO::ROLE_SCENE_LINEAR, kSceneLinear);
    cfg->setRole(OCIO::ROLE_DEFAULT, kSceneLinear);
    cfg->setRole(OCIO::ROLE_REFERENCE, "ACEScg");
    cfg->validate();
    return cfg;
}

// The display-view processor from scene_linear of `config` (NULL: built-in) to
// display/view (NULL: the config's defaults); inverse for reading display-referred files.
OCIO::ConstCPUProcessorRcPtr display_processor(const char *config, const char *display,
                                               const char *view, bool inverse)
{
    OCIO::ConstConfigRcPtr cfg =
        (config && *config) ? OCIO::Config::CreateFromFile(config) : builtin_config();
    std::string disp = (display && *display) ? display : cfg->getDefaultDisplay();
    std::string v = (view && *view) ? view : cfg->getDefaultView(disp.c_str());
    if (cfg->getNumViews(disp.c_str()) == 0)
        throw std::runtime_error("OpenColorIO config has no display '" + disp + "'");
    bool found = false;
    for (int i = 0; i < cfg->getNumViews(disp.c_str()); ++i)
        if (v == cfg->getView(disp.c_str(), i)) found = true;
    if (!found) throw std::runtime_error("display '" + disp + "' has no view '" + v + "'");
    OCIO::ConstColorSpaceRcPtr lin = cfg->getColorSpace(OCIO::ROLE_SCENE_LINEAR);
    if (!lin) throw std::runtime_error("OpenColorIO config has no scene_linear role");
    OCIO::DisplayViewTransformRcPtr dv = OCIO::DisplayViewTransform::Create();
    dv->setSrc(lin->getName());
    dv->setDisplay(disp.c_str());
    dv->setView(v.c_str());
    OCIO::ConstProcessorRcPtr proc =
        cfg->getProcessor(dv, inverse ? OCIO::TRANSFORM_DIR_INVERSE : OCIO::TRANSFORM_DIR_FORWARD);
    return proc->getDefaultCPUProcessor();
}

bool valid_size(int width, int height, const void *data, char *err, int err_size)
{
    if (width <= 0 || height <= 0 || (long long)width * height > kMaxPixels) {
        set_err(err, err_size,
                "invalid image size " + std::to_string(width) + "x" + std::to_string(height));
        return false;
    }
    if (!data) {
        set_err(err, err_size, "no pixel data");
        return false;
    }
    return true;
}

// Can a file named `name` be encoded in memory? Returns the reason if not.
std::string encodable(const char *name)
{
    auto out = OIIO::ImageOutput::create(name);
    if (!out) {
        std::string e = OIIO::geterror();
        return e.empty() ? "no image format for this extension" : e;
    }
    if (!out->supports("ioproxy"))
        return std::string("OpenImageIO's ") + out->format_name() +
               " writer cannot encode in memory, so its writes could not be checked; write "
               ".exr, .hdr, .tif, .png or .jpg";
    return "";
}

// Encode w x h x nch floats as the format of `name`, pixel type `type` (UINT8 for display
// files), into out.
int encode(const char *name, int width, int height, int nch, const float *data, OIIO::TypeDesc type,
           const char *colorspace, abrdf_bytes *out, char *err, int err_size)
{
    std::string why = encodable(name);
    if (!why.empty()) {
        set_err_path(err, err_size, name, why);
        return -1;
    }
    auto io = OIIO::ImageOutput::create(name);
    std::vector<unsigned char> bytes;
    OIIO::Filesystem::IOVecOutput vec(bytes);
    OIIO::ImageSpec spec(width, height, nch, type);
    spec.attribute("oiio:ColorSpace", colorspace);
    spec.attribute("Software", "abrdf");
    // libtiff cannot write the Exif directory through an in-memory proxy (OpenImageIO 2.4:
    // "failed TIFFWriteCustomDirectory() of the Exif data"); abrdf writes no Exif data.
    spec.attribute("tiff:write_exif", 0);
    if (!io->set_ioproxy(&vec) || !io->open(name, spec) ||
        !io->write_image(OIIO::TypeDesc::FLOAT, data) || !io->close() || io->has_error()) {
        set_err_path(err, err_size, name, io->geterror());
        return -1;
    }
    out->data = (unsigned char *)std::malloc(bytes.size() ? bytes.size() : 1);
    if (!out->data) {
        set_err_path(err, err_size, name, "out of memory");
        return -1;
    }
    std::memcpy(out->data, bytes.data(), bytes.size());
    out->size = bytes.size();
    return 0;
}

} // namespace

extern "C" int abrdf_image_is_display_format(const char *path)
{
    static const char *const display_ext[] = {"png",  "jpg", "jpeg", "bmp", "gif",
                                              "webp", "ppm", "pgm",  "pnm"};
    if (!path) return 0;
    std::string ext = lower_ext(path);
    for (const char *e : display_ext)
        if (ext == e) return 1;
    return 0;
}

extern "C" void abrdf_bytes_free(abrdf_bytes *b)
{
    if (!b) return;
    std::free(b->data);
    b->data = nullptr;
    b->size = 0;
}

extern "C" int abrdf_image_check_output(const char *name, int linear, char *err, int err_size)
{
    try {
        if (!name || !*name) {
            set_err(err, err_size, "no output name");
            return -1;
        }
        if (linear && abrdf_image_is_display_format(name)) {
            set_err_path(err, err_size, name,
                         "an 8-bit display format cannot hold scene-linear data; write "
                         ".exr/.hdr/.tif (or a preview)");
            return -1;
        }
        if (!linear && !abrdf_image_is_display_format(name)) {
            set_err_path(err, err_size, name,
                         "not an 8-bit display format; write .png, .jpg, .bmp, .gif, .webp or "
                         ".ppm");
            return -1;
        }
        std::string why = encodable(name);
        if (why.empty()) return 0;
        set_err_path(err, err_size, name, why);
    } catch (const std::exception &e) {
        set_err_path(err, err_size, name, e.what());
    } catch (...) {
        set_err(err, err_size, "unexpected error checking an output name");
    }
    return -1;
}

extern "C" int abrdf_image_check_preview(const char *config, const char *display, const char *view,
                                         char *err, int err_size)
{
    try {
        display_processor(config, display, view, false);
        return 0;
    } catch (const std::exception &e) {
        set_err(err, err_size, std::string("preview transform: ") + e.what());
    } catch (...) {
        set_err(err, err_size, "preview transform: unexpected error");
    }
    return -1;
}

namespace
{

// A scene-linear file of `name`'s format: 32-bit float where the format has it (EXR, TIFF;
// .hdr stores its own RGBE encoding), or half floats (EXR only).
int encode_linear(const char *name, int width, int height, const float *rgb, bool half,
                  abrdf_bytes *out, char *err, int err_size)
{
    if (!out) return -1;
    out->data = nullptr;
    out->size = 0;
    try {
        if (!name || !*name || !valid_size(width, height, rgb, err, err_size)) {
            if (!name || !*name) set_err(err, err_size, "no output name");
            return -1;
        }
        if (half && lower_ext(name) != "exr") {
            set_err_path(err, err_size, name, "half floats are written as .exr only");
            return -1;
        }
        if (abrdf_image_check_output(name, 1, err, err_size)) return -1;
        return encode(name, width, height, 3, rgb,
                      half ? OIIO::TypeDesc::HALF : OIIO::TypeDesc::FLOAT, "Linear", out, err,
                      err_size);
    } catch (const std::exception &e) {
        set_err_path(err, err_size, name, e.what());
    } catch (...) {
        set_err(err, err_size, "unexpected error encoding an image");
    }
    abrdf_bytes_free(out);
    return -1;
}

} // namespace

extern "C" int abrdf_image_encode_linear(const char *name, int width, int height, const float *rgb,
                                         abrdf_bytes *out, char *err, int err_size)
{
    return encode_linear(name, width, height, rgb, false, out, err, err_size);
}

extern "C" int abrdf_image_encode_linear_half(const char *name, int width, int height,
                                              const float *rgb, abrdf_bytes *out, char *err,
                                              int err_size)
{
    return encode_linear(name, width, height, rgb, true, out, err, err_size);
}

extern "C" int abrdf_image_encode_preview(const char *name, int width, int height, const float *rgb,
                                          const char *config, const char *display, const char *view,
                                          abrdf_bytes *out, char *err, int err_size)
{
    if (!out) return -1;
    out->data = nullptr;
    out->size = 0;
    try {
        if (!name || !valid_size(width, height, rgb, err, err_size)) {
            if (!name) set_err(err, err_size, "no output name");
            return -1;
        }
        std::vector<float> buf(rgb, rgb + (size_t)width * height * 3);
        OCIO::ConstCPUProcessorRcPtr cpu = display_processor(config, display, view, false);
        OCIO::PackedImageDesc desc(buf.data(), width, height, 3);
        cpu->apply(desc);
        // OpenImageIO quantises to 8 bits (clamping to [0,1], rounding to nearest).
        return encode(name, width, height, 3, buf.data(), OIIO::TypeDesc::UINT8, "sRGB", out, err,
                      err_size);
    } catch (const std::exception &e) {
        set_err_path(err, err_size, name, e.what());
    } catch (...) {
        set_err(err, err_size, "unexpected error encoding a preview");
    }
    abrdf_bytes_free(out);
    return -1;
}

extern "C" int abrdf_image_encode_heatmap(const char *name, int width, int height,
                                          const float *value, double vmax, const char *map,
                                          abrdf_bytes *out, char *err, int err_size)
{
    if (!out) return -1;
    out->data = nullptr;
    out->size = 0;
    try {
        if (!name || !valid_size(width, height, value, err, err_size)) {
            if (!name) set_err(err, err_size, "no output name");
            return -1;
        }
        OIIO::ImageBuf src(OIIO::ImageSpec(width, height, 1, OIIO::TypeDesc::FLOAT));
        std::vector<float> v((size_t)width * height);
        double scale = vmax > 0 ? 1.0 / vmax : 0.0;
        for (size_t i = 0; i < v.size(); ++i)
            v[i] = (float)std::min(1.0, std::max(0.0, (double)value[i] * scale));
        src.set_pixels(OIIO::ROI(0, width, 0, height, 0, 1, 0, 1), OIIO::TypeDesc::FLOAT, v.data());
        OIIO::ImageBuf col = OIIO::ImageBufAlgo::color_map(src, 0, (map && *map) ? map : "inferno");
        if (col.has_error()) {
            set_err_path(err, err_size, name, col.geterror());
            return -1;
        }
        // The colour maps are defined in display (sRGB-encoded) values: encode them as they are.
        int nch = col.nchannels();
        std::vector<float> px((size_t)width * height * nch);
        if (!col.get_pixels(OIIO::ROI(0, width, 0, height, 0, 1, 0, nch), OIIO::TypeDesc::FLOAT,
                            px.data())) {
            set_err_path(err, err_size, name, col.geterror());
            return -1;
        }
        return encode(name, width, height, nch, px.data(), OIIO::TypeDesc::UINT8, "sRGB", out, err,
                      err_size);
    } catch (const std::exception &e) {
        set_err_path(err, err_size, name, e.what());
    } catch (...) {
        set_err(err, err_size, "unexpected error encoding a heat map");
    }
    abrdf_bytes_free(out);
    return -1;
}

namespace
{

// The image's rows in strips of channels [0, colour) as floats, into malloc'd RGB (grey
// replicated): the buffer grows strip by strip, up to width * height * 3 floats. NULL after
// the message on a read error.
float *read_rows(OIIO::ImageInput *in, const OIIO::ImageSpec &spec, int colour, const char *path,
                 char *err, int err_size)
{
    const int w = spec.width, h = spec.height;
    // tiles are read whole: a strip is a whole number of tile rows
    const int rows = spec.tile_height > 0
                         ? spec.tile_height * std::max(1, kStripRows / spec.tile_height)
                         : kStripRows;
    // not value-initialised: a strip is written by the read before it is used
    std::unique_ptr<float[]> part;
    size_t part_size = 0;
    float *rgb = nullptr;
    size_t cap = 0; // floats
    for (int y0 = 0; y0 < h; y0 += rows) {
        int y1 = std::min(h, y0 + rows);
        size_t need_part = (size_t)w * (size_t)(y1 - y0) * (size_t)colour;
        if (need_part > part_size) part.reset(new float[need_part]), part_size = need_part;
        bool ok = spec.tile_width > 0
                      ? in->read_tiles(0, 0, spec.x, spec.x + w, spec.y + y0, spec.y + y1, spec.z,
                                       spec.z + 1, 0, colour, OIIO::TypeDesc::FLOAT, part.get())
                      : in->read_scanlines(0, 0, spec.y + y0, spec.y + y1, spec.z, 0, colour,
                                           OIIO::TypeDesc::FLOAT, part.get());
        // a reader may fill what it could not read and say so only in its error state
        // (a truncated TIFF strip)
        if (!ok || in->has_error()) {
            std::string e = in->geterror();
            set_err_path(err, err_size, path, e.empty() ? "read error" : e);
            std::free(rgb);
            return nullptr;
        }
        size_t need = (size_t)w * (size_t)y1 * 3;
        if (need > cap) {
            size_t grown = std::min((size_t)w * (size_t)h * 3, std::max(need, 2 * cap));
            float *g = (float *)std::realloc(rgb, grown * sizeof(float));
            if (!g) {
                set_err_path(err, err_size, path, "out of memory");
                std::free(rgb);
                return nullptr;
            }
            rgb = g, cap = grown;
        }
        float *dst = rgb + (size_t)w * (size_t)y0 * 3;
        for (size_t p = 0; p < (size_t)w * (size_t)(y1 - y0); ++p)
            for (int c = 0; c < 3; ++c) dst[p * 3 + c] = part[p * colour + (colour == 3 ? c : 0)];
    }
    return rgb;
}

// OpenEXR's core (C) reader: the header alone, before OpenImageIO's reader (OpenEXR's C++
// library), which sizes its buffers by what a header declares (an attribute's length, the
// offset table of every block) before it finds that the file does not hold them.
thread_local std::string exr_core_message;
void exr_keep_message(exr_const_context_t, exr_result_t, const char *msg)
{
    if (exr_core_message.empty() && msg) exr_core_message = msg;
}

bool has_exr_magic(const char *path)
{
    unsigned char magic[4] = {0, 0, 0, 0};
    FILE *f = std::fopen(path, "rb");
    size_t got = f ? std::fread(magic, 1, 4, f) : 0;
    if (f) std::fclose(f);
    return got == 4 && magic[0] == 0x76 && magic[1] == 0x2f && magic[2] == 0x31 && magic[3] == 0x01;
}

// An EXR's header against its file: the header must read without an error in OpenEXR's core
// reader (every attribute within the file), and every block it declares has an 8-byte entry in the
// offset table after it, so a header that declares more blocks than the file could hold (a
// mutated tile size or data window) is refused before any reader sizes a table after it.
// Also the reader's pixel limit. "" if the header is plausible or the file is no EXR, else
// the reason.
std::string exr_header_problem(const char *path, off_t file_size)
{
    if (!has_exr_magic(path)) return "";
    exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
    init.error_handler_fn = exr_keep_message;
    exr_context_t ctx = nullptr;
    exr_core_message.clear();
    // the core reader passes over some broken attributes, which the C++ reader would size
    if (exr_start_read(&ctx, path, &init) != EXR_ERR_SUCCESS || !exr_core_message.empty()) {
        exr_finish(&ctx);
        std::string why = exr_core_message.empty() ? "not a readable EXR header"
                                                   : "EXR header: " + exr_core_message;
        exr_core_message.clear();
        return why;
    }
    std::string why;
    int parts = 0;
    long long blocks = 0;
    exr_get_count(ctx, &parts);
    for (int p = 0; p < parts && why.empty(); ++p) {
        int32_t n = 0;
        exr_attr_box2i_t dw;
        if (exr_get_data_window(ctx, p, &dw) == EXR_ERR_SUCCESS) {
            long long w = (long long)dw.max.x - dw.min.x + 1,
                      h = (long long)dw.max.y - dw.min.y + 1;
            if (w * h > kMaxPixels)
                why = "unsupported image (size " + std::to_string(w) + "x" + std::to_string(h) +
                      ", over " + std::to_string(kMaxPixels) + " pixels)";
        }
        if (exr_get_chunk_count(ctx, p, &n) == EXR_ERR_SUCCESS) blocks += n;
    }
    exr_finish(&ctx);
    if (why.empty() && 8 * blocks > (long long)file_size)
        why = "its header declares " + std::to_string(blocks) + " blocks of pixels, whose offset " +
              "table alone needs " + std::to_string(8 * blocks) + " bytes; the file has " +
              std::to_string((long long)file_size) + " (truncated or corrupt)";
    return why;
}

} // namespace

extern "C" int abrdf_image_read(const char *path, abrdf_image *img, char *err, int err_size)
{
    if (!img) return -1;
    img->width = img->height = img->channels = 0;
    img->pixels = nullptr;
    try {
        if (!path) {
            set_err(err, err_size, "no input path");
            return -1;
        }
        // A FIFO or a device would block OpenImageIO's open, a directory has no image.
        struct stat st;
        if (stat(path, &st) != 0) {
            set_err_path(err, err_size, path, std::string("cannot open: ") + std::strerror(errno));
            return -1;
        }
        if (!S_ISREG(st.st_mode)) { // the words of the other readers (tools/common/in_file.c)
            const mode_t m = st.st_mode;
            set_err_path(err, err_size, path,
                         S_ISDIR(m)    ? "is a directory, not a file"
                         : S_ISFIFO(m) ? "is a FIFO, not a regular file"
                         : S_ISCHR(m)  ? "is a character device, not a regular file"
                         : S_ISBLK(m)  ? "is a block device, not a regular file"
                         : S_ISSOCK(m) ? "is a socket, not a regular file"
                                       : "is not a regular file");
            return -1;
        }
        std::string bad = exr_header_problem(path, st.st_size);
        if (!bad.empty()) {
            set_err_path(err, err_size, path, bad);
            return -1;
        }
        auto in = OIIO::ImageInput::open(path);
        if (!in) {
            std::string e = OIIO::geterror();
            set_err_path(err, err_size, path, e.empty() ? "cannot open" : e);
            return -1;
        }
        const OIIO::ImageSpec spec = in->spec();
        int w = spec.width, h = spec.height, nch = spec.nchannels;
        if (w <= 0 || h <= 0 || nch <= 0 || (long long)w * h > kMaxPixels || spec.deep ||
            spec.depth > 1) {
            set_err_path(err, err_size, path,
                         "unsupported image (size " + std::to_string(w) + "x" + std::to_string(h) +
                             ", " + std::to_string(nch) + " channels" +
                             (spec.deep ? ", deep" : "") + (spec.depth > 1 ? ", a volume" : "") +
                             ")");
            return -1;
        }
        // RGB from the first three channels; grey (and grey+alpha) is replicated: only those
        // channels are read.
        int colour = (nch >= 3 && spec.alpha_channel != 1 && spec.alpha_channel != 2) ? 3 : 1;
        long long bytes = (long long)w * h * colour * (long long)sizeof(float);
        if (bytes > kMaxReadBytes) {
            set_err_path(err, err_size, path,
                         std::to_string(w) + "x" + std::to_string(h) + " pixels x " +
                             std::to_string(colour) + " channels as 32-bit floats need " +
                             std::to_string(bytes) + " bytes, over the image reader's limit of " +
                             std::to_string(kMaxReadBytes) + " bytes");
            return -1;
        }
        float *rgb = read_rows(in.get(), spec, colour, path, err, err_size);
        if (!rgb) return -1;
        in->close();
        // Display-referred files (tagged sRGB, or untagged integer data) are decoded to
        // scene-linear with the inverse of the built-in sRGB display transform.
        std::string cs = spec.get_string_attribute("oiio:ColorSpace");
        for (char &c : cs) c = (char)std::tolower((unsigned char)c);
        bool integer = spec.format.basetype != OIIO::TypeDesc::FLOAT &&
                       spec.format.basetype != OIIO::TypeDesc::HALF &&
                       spec.format.basetype != OIIO::TypeDesc::DOUBLE;
        if (cs == "srgb" || (cs.empty() && integer)) {
            try {
                OCIO::ConstCPUProcessorRcPtr cpu =
                    display_processor(nullptr, nullptr, nullptr, true);
                OCIO::PackedImageDesc desc(rgb, w, h, 3);
                cpu->apply(desc);
            } catch (...) {
                std::free(rgb);
                throw;
            }
        }
        img->width = w;
        img->height = h;
        img->channels = nch;
        img->pixels = rgb;
        return 0;
    } catch (const std::bad_alloc &) {
        set_err_path(err, err_size, path, "out of memory");
    } catch (const std::exception &e) {
        set_err_path(err, err_size, path, e.what());
    } catch (...) {
        set_err(err, err_size, "unexpected error reading an image");
    }
    return -1;
}

extern "C" void abrdf_image_free(abrdf_image *img)
{
    if (!img) return;
    std::free(img->pixels);
    img->pixels = nullptr;
    img->width = img->height = img->channels = 0;
}
