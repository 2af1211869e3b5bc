// texture.cpp - texture.h over OpenImageIO's TextureSystem, built as the module
// libabrdf_texture.so: one exported entry point (abrdf_texture_module) hands texture_lazy.c
// the table of the functions below. Nothing throws across it.
#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imagecache.h>
#include <OpenImageIO/texture.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "texture_module.h"

using namespace OIIO;

struct texture_file {
    ustring name;
    TextureSystem::TextureHandle *handle;
    int channels;
};

struct texture_thread {
    TextureSystem::Perthread *info;
};

struct texture_system {
    ImageCache *ic;
    TextureSystem *ts;
    TextureOpt opt;
    std::vector<std::unique_ptr<texture_file>> files;
    std::vector<std::unique_ptr<Filesystem::IOMemReader>> proxies; // in-memory images
    // Thread states are kept for reuse until the system goes: OpenImageIO 2.4 merges the
    // statistics of every state it made, destroyed or not (a destroyed one crashes getstats),
    // so they are destroyed last, with the system.
    std::mutex lock;
    std::vector<texture_thread *> idle, all;
    std::string first_error; // of a lookup (under lock): "NAME: problem"
};

namespace
{

void say(char *err, size_t err_size, const std::string &msg)
{
    if (!err || err_size == 0) return;
    // OpenImageIO's messages may span lines: keep one line
    std::string one = msg;
    for (char &c : one)
        if (c == '\n' || c == '\r') c = ' ';
    while (!one.empty() && one.back() == ' ') one.pop_back();
    std::snprintf(err, err_size, "%s", one.c_str());
}

texture_system *system_new(double cache_mb, char *err, size_t err_size)
{
    if (!(cache_mb >= TEXTURE_CACHE_MB_MIN && cache_mb <= TEXTURE_CACHE_MB_MAX)) {
        std::snprintf(err, err_size, "texture cache of %g MB is outside [%g, %g]", cache_mb,
                      TEXTURE_CACHE_MB_MIN, TEXTURE_CACHE_MB_MAX);
        return nullptr;
    }
    try {
        std::unique_ptr<texture_system> s(new texture_system);
        s->ic = ImageCache::create(false);
        s->ic->attribute("max_memory_MB", float(cache_mb));
        s->ic->attribute("autotile", 64); // scanline files cached in 64 x 64 tiles
        s->ic->attribute("automip", 1);   // ... with their MIP levels made on demand
        // (not "forcefloat": OpenImageIO 2.4 fails an assertion in bilinear lookups of 8-bit
        // files with it)
        s->ts = TextureSystem::create(false, s->ic);
        s->opt.swrap = s->opt.twrap = TextureOpt::WrapPeriodic; // glTF's REPEAT
        s->opt.interpmode = TextureOpt::InterpBilinear;         // texel centres exact
        s->opt.mipmode = TextureOpt::MipModeAniso;
        return s.release();
    } catch (const std::exception &e) {
        say(err, err_size, std::string("cannot make a texture system: ") + e.what());
    }
    return nullptr;
}

void system_free(texture_system *s)
{
    if (!s) return;
    for (texture_thread *t : s->all) {
        s->ts->destroy_thread_info(t->info); // nothing reads the statistics after this
        delete t;
    }
    TextureSystem::destroy(s->ts);
    ImageCache::destroy(s->ic);
    delete s;
}

int open_file(texture_system *s, const char *name, const void *bytes, size_t size,
              texture_file **out, texture_info *info, char *err, size_t err_size)
{
    *out = nullptr;
    try {
        ustring un(name);
        for (auto &f : s->files)
            if (f->name == un && !bytes) {
                *out = f.get();
                break;
            }
        if (bytes) {
            if (!size) {
                say(err, err_size, std::string(name) + ": an empty image");
                return -1;
            }
            std::string ext = Filesystem::extension(name, false);
            auto probe = ImageInput::create(ext.empty() ? std::string(name) : ext, false);
            if (!probe || !probe->supports("ioproxy")) {
                say(err, err_size,
                    std::string(name) + ": OpenImageIO " + OIIO_VERSION_STRING +
                        " cannot read this image format from memory" +
                        (ext.empty() ? " (no extension names the format)" : ""));
                return -1;
            }
            s->proxies.emplace_back(new Filesystem::IOMemReader(bytes, size));
            ImageSpec config;
            void *proxy = s->proxies.back().get();
            config.attribute("oiio:ioproxy", TypeDesc::PTR, &proxy);
            s->ic->add_file(un, nullptr, &config, true);
        }
        if (!*out) {
            std::unique_ptr<texture_file> f(new texture_file);
            f->name = un;
            f->handle = s->ts->get_texture_handle(un);
            ImageSpec spec;
            if (!f->handle || !s->ts->get_imagespec(f->handle, nullptr, 0, spec)) {
                // OpenImageIO's first line says why; the next ones repeat it with the name
                std::string why = s->ts->geterror();
                why = why.substr(0, why.find('\n'));
                if (why.empty()) why = "cannot be read as an image";
                // OpenImageIO names the file itself at times: do not say it twice
                if (why.compare(0, std::strlen(name), name) == 0)
                    say(err, err_size, why);
                else
                    say(err, err_size, std::string(name) + ": " + why);
                return -1;
            }
            if (spec.width < 1 || spec.height < 1 || spec.depth != 1 || spec.nchannels < 1) {
                say(err, err_size, std::string(name) + ": not a 2D image");
                return -1;
            }
            f->channels = spec.nchannels;
            s->files.push_back(std::move(f));
            *out = s->files.back().get();
        }
        if (info) {
            ImageSpec spec;
            s->ts->get_imagespec((*out)->handle, nullptr, 0, spec);
            info->width = spec.width, info->height = spec.height;
            info->channels = spec.nchannels;
            info->tiled = spec.tile_width > 0;
            int levels = 1;
            s->ic->get_image_info((*out)->name, 0, 0, ustring("miplevels"), TypeInt, &levels);
            info->levels = levels;
        }
        return 0;
    } catch (const std::exception &e) {
        say(err, err_size, std::string(name) + ": " + e.what());
    }
    return -1;
}

texture_thread *thread_new(texture_system *s)
{
    try {
        std::lock_guard<std::mutex> g(s->lock);
        if (!s->idle.empty()) {
            texture_thread *t = s->idle.back();
            s->idle.pop_back();
            return t;
        }
        std::unique_ptr<texture_thread> t(new texture_thread);
        t->info = s->ts->create_thread_info();
        s->all.reserve(s->all.size() + 1);
        s->idle.reserve(s->all.size() + 1); // thread_free cannot fail to keep it
        s->all.push_back(t.get());
        return t.release();
    } catch (...) {
        return nullptr;
    }
}

void thread_free(texture_system *s, texture_thread *t)
{
    if (!t) return;
    std::lock_guard<std::mutex> g(s->lock);
    s->idle.push_back(t);
}

int lookup(texture_system *s, texture_thread *t, texture_file *f, int first, int n, double ss,
           double tt, double dsdx, double dtdx, double dsdy, double dtdy, float *out)
{
    TextureOpt opt = s->opt;
    opt.firstchannel = first;
    bool ok = s->ts->texture(f->handle, t->info, opt, float(ss), float(tt), float(dsdx),
                             float(dtdx), float(dsdy), float(dtdy), n, out);
    if (ok) return 0;
    std::string why = s->ts->geterror(); // also clears this thread's message
    why = why.substr(0, why.find('\n'));
    {
        std::lock_guard<std::mutex> g(s->lock);
        if (s->first_error.empty()) {
            if (why.compare(0, f->name.size(), f->name.string()) != 0)
                why = f->name.string() + ": " + (why.empty() ? "a lookup failed" : why);
            s->first_error = why;
        }
    }
    for (int c = 0; c < n; ++c) out[c] = 0;
    return -1;
}

long long stat_int64(texture_system *s, const char *name)
{
    long long v = 0;
    s->ts->getattribute(name, TypeDesc::INT64, &v);
    return v;
}

int stat_int(texture_system *s, const char *name)
{
    int v = 0;
    s->ts->getattribute(name, TypeInt, &v);
    return v;
}

void stats_get(texture_system *s, texture_stats *out)
{
    std::memset(out, 0, sizeof *out);
    out->bytes_read = (unsigned long long)stat_int64(s, "stat:bytes_read");
    out->memory_used = stat_int64(s, "stat:cache_memory_used");
    out->tiles_peak = stat_int(s, "stat:tiles_peak");
    out->files = stat_int(s, "stat:unique_files");
    // The peak memory is only in the report: "Peak cache memory : 3.2 MB"
    out->peak_memory_mb = -1;
    std::string r = s->ts->getstats(1); // the texture report, then the cache's
    // "Queries/batches :\n    texture     :  10 queries in 10 batches"
    size_t q = r.find("Queries/batches");
    if (q != std::string::npos) q = r.find("texture", q + 15);
    if (q != std::string::npos) q = r.find(':', q);
    if (q != std::string::npos) out->lookups = std::strtoull(r.c_str() + q + 1, nullptr, 10);
    size_t at = r.find("Peak cache memory");
    if (at != std::string::npos) {
        at = r.find(':', at);
        double v;
        char unit[8] = "";
        if (at != std::string::npos && std::sscanf(r.c_str() + at + 1, "%lf %7s", &v, unit) >= 1) {
            double scale = !std::strcmp(unit, "GB")   ? 1024.0
                           : !std::strcmp(unit, "KB") ? 1.0 / 1024
                           : !std::strcmp(unit, "B")  ? 1.0 / (1024.0 * 1024.0)
                                                      : 1.0;
            out->peak_memory_mb = v * scale;
        }
    }
}

int first_error(texture_system *s, char *err, size_t err_size)
{
    std::lock_guard<std::mutex> g(s->lock);
    if (s->first_error.empty()) return 0;
    say(err, err_size, s->first_error);
    return -1;
}

void stats_print(texture_system *s, int level, FILE *f)
{
    std::fputs(s->ts->getstats(level).c_str(), f);
    std::fputc('\n', f);
}

double srgb_decode(double v)
{
    return v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4);
}

int channel_stats(texture_system *s, texture_file *f, int level, int channel, int srgb, int nbins,
                  unsigned long long *hist, double *mn, double *mx, char *err, size_t err_size)
{
    const char *name = f->name.c_str();
    if (channel < 0 || channel >= f->channels) {
        std::snprintf(err, err_size, "%s: no channel %d (the image has %d)", name, channel,
                      f->channels);
        return -1;
    }
    if (nbins < 1) {
        std::snprintf(err, err_size, "%s: %d histogram bins", name, nbins);
        return -1;
    }
    try {
        ImageSpec spec;
        if (!s->ic->get_imagespec(f->name, spec, 0, level)) {
            std::string why = s->ic->geterror();
            say(err, err_size,
                std::string(name) + ": no MIP level " + std::to_string(level) +
                    (why.empty() ? "" : " (" + why + ")"));
            return -1;
        }
        std::vector<float> row((size_t)spec.width);
        std::fill(hist, hist + nbins, 0ull);
        double lo = INFINITY, hi = -INFINITY;
        for (int y = spec.y; y < spec.y + spec.height; ++y) {
            if (!s->ic->get_pixels(f->name, 0, level, spec.x, spec.x + spec.width, y, y + 1, 0, 1,
                                   channel, channel + 1, TypeFloat, row.data())) {
                say(err, err_size, std::string(name) + ": " + s->ic->geterror());
                return -1;
            }
            for (float fv : row) {
                double v = fv;
                if (std::isnan(v)) continue;
                if (srgb) v = srgb_decode(v);
                lo = std::fmin(lo, v), hi = std::fmax(hi, v);
                int b = v <= 0 ? 0 : v >= 1 ? nbins - 1 : (int)(v * nbins);
                ++hist[b < nbins ? b : nbins - 1];
            }
        }
        *mn = lo, *mx = hi;
        return 0;
    } catch (const std::exception &e) {
        say(err, err_size, std::string(name) + ": " + e.what());
    }
    return -1;
}

const texture_module_api api = {TEXTURE_MODULE_VERSION,
                                system_new,
                                system_free,
                                open_file,
                                thread_new,
                                thread_free,
                                lookup,
                                stats_get,
                                stats_print,
                                channel_stats,
                                first_error};

} // namespace

extern "C" __attribute__((visibility("default"))) const texture_module_api *
abrdf_texture_module(void)
{
    return &api;
}
