// mesh_obj.cpp - mesh_obj.h over tinyobjloader's streaming interface (LoadObjWithCallback).
// The text stays in memory; a stream buffer over it lets the wrapper see how far the
// library has read, so every statement reaches the sink with its line, and every line the
// library passed over reaches the sink's `other`. Line ends are the library's: "\n",
// "\r\n" or a lone "\r".
#include "mesh_obj.h"

#include <tiny_obj_loader.h>

#include <cstdio>
#include <exception>
#include <istream>
#include <new>
#include <streambuf>
#include <vector>

namespace
{

// The text as a read-only stream; position() is how far the library has consumed it.
class text_buf : public std::streambuf
{
  public:
    text_buf(const char *text, size_t len)
    {
        char *p = const_cast<char *>(text); // never written: no put area, no putback
        setg(p, p, p + len);
    }
    size_t position() const { return (size_t)(gptr() - eback()); }
    void stop() { setg(egptr(), egptr(), egptr()); }
};

struct walker {
    const char *text;
    size_t len;
    size_t cursor; // start of the first line not yet given to the sink
    int number;    // number of the line at cursor
    text_buf *buf;
    const mesh_obj_sink *sink;
    int stopped;
    mesh_obj_line current;

    // Line at cursor: its text length and the offset after its end.
    size_t line_end(size_t *next) const
    {
        size_t e = cursor;
        while (e < len && text[e] != '\n' && text[e] != '\r') ++e;
        size_t n = e;
        if (n < len) n += (text[n] == '\r' && n + 1 < len && text[n + 1] == '\n') ? 2 : 1;
        *next = n;
        return e - cursor;
    }

    // The library has read up to `pos`: the last line ending there is the statement it
    // has just parsed (it becomes `current`); the lines before it went by without one.
    bool sync(size_t pos)
    {
        while (cursor < pos) {
            size_t next, l = line_end(&next);
            mesh_obj_line line = {number, text + cursor, l};
            cursor = next;
            ++number;
            if (next >= pos) {
                current = line;
                return true;
            }
            if (sink->other && sink->other(sink->user, &line)) return fail();
        }
        return true;
    }

    // After the library's last statement: the remaining lines.
    void finish()
    {
        while (!stopped && cursor < len) {
            size_t next, l = line_end(&next);
            mesh_obj_line line = {number, text + cursor, l};
            cursor = next;
            ++number;
            if (sink->other && sink->other(sink->user, &line)) stopped = 1;
        }
    }

    bool fail()
    {
        stopped = 1;
        buf->stop();
        return false;
    }
};

walker *as_walker(void *user) { return static_cast<walker *>(user); }

void on_vertex(void *user, tinyobj::real_t x, tinyobj::real_t y, tinyobj::real_t z, tinyobj::real_t)
{
    walker *w = as_walker(user);
    if (w->stopped || !w->sync(w->buf->position())) return;
    if (w->sink->vertex && w->sink->vertex(w->sink->user, &w->current, x, y, z)) w->fail();
}

void on_normal(void *user, tinyobj::real_t x, tinyobj::real_t y, tinyobj::real_t z)
{
    walker *w = as_walker(user);
    if (w->stopped || !w->sync(w->buf->position())) return;
    if (w->sink->normal && w->sink->normal(w->sink->user, &w->current, x, y, z)) w->fail();
}

void on_texcoord(void *user, tinyobj::real_t u, tinyobj::real_t v, tinyobj::real_t)
{
    walker *w = as_walker(user);
    if (w->stopped || !w->sync(w->buf->position())) return;
    if (w->sink->texcoord && w->sink->texcoord(w->sink->user, &w->current, u, v)) w->fail();
}

void on_face(void *user, tinyobj::index_t *idx, int count)
{
    walker *w = as_walker(user);
    if (w->stopped || !w->sync(w->buf->position())) return;
    std::vector<int> v((size_t)count), vt((size_t)count), vn((size_t)count);
    for (int i = 0; i < count; ++i) {
        v[(size_t)i] = idx[i].vertex_index;
        vt[(size_t)i] = idx[i].texcoord_index;
        vn[(size_t)i] = idx[i].normal_index;
    }
    if (w->sink->face &&
        w->sink->face(w->sink->user, &w->current, v.data(), vt.data(), vn.data(), count))
        w->fail();
}

} // namespace

extern "C" int mesh_obj_parse(const char *text, size_t len, const mesh_obj_sink *sink, char *err,
                              size_t err_size)
{
    try {
        text_buf buf(text, len);
        std::istream in(&buf);
        walker w = {text, len, 0, 1, &buf, sink, 0, {0, text, 0}};
        tinyobj::callback_t cb;
        cb.vertex_cb = on_vertex;
        cb.normal_cb = on_normal;
        cb.texcoord_cb = on_texcoord;
        cb.index_cb = on_face;
        // No material reader: materials come from the scene, an mtllib line is passed over.
        tinyobj::LoadObjWithCallback(in, cb, &w, nullptr, nullptr, nullptr);
        w.finish();
        return w.stopped ? -1 : 0;
    } catch (const std::bad_alloc &) {
        if (err && err_size) std::snprintf(err, err_size, "out of memory");
    } catch (const std::exception &e) {
        if (err && err_size) std::snprintf(err, err_size, "OBJ reader: %s", e.what());
    }
    return -2;
}
