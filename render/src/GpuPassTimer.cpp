#include "throng/render/GpuPassTimer.h"

#include <stdexcept>

#include <glad/gl.h>

#include "throng/render/GlContext.h"

namespace throng {

GpuPassTimer::GpuPassTimer(GlContext& context) : context_(context) {
    context_.makeCurrent();
    for (Set& s : sets_) context_.gl().GenQueries(GLsizei(s.queries.size()), s.queries.data());
}

GpuPassTimer::~GpuPassTimer() {
    try {
        context_.makeCurrent();
        for (Set& s : sets_) context_.gl().DeleteQueries(GLsizei(s.queries.size()), s.queries.data());
    } catch (...) {
    }  // a context that cannot be made current frees its queries with itself
}

void GpuPassTimer::read(Set& set) {
    if (set.frame < 0) return;
    const GladGLContext& g = context_.gl();
    GpuPassTimes times;
    for (std::size_t p = 0; p < set.queries.size(); ++p) {
        if (!set.used[p]) continue;
        GLint available = 0;
        g.GetQueryObjectiv(set.queries[p], GL_QUERY_RESULT_AVAILABLE, &available);
        if (!available) return;  // not yet: asked again later, never waited for
        GLuint64 ns = 0;
        g.GetQueryObjectui64v(set.queries[p], GL_QUERY_RESULT, &ns);
        times.ms[p] = double(ns) * 1e-6;
    }
    times.frame = set.frame;
    if (times.frame > latest_.frame) latest_ = times;
    set.frame = -1;
}

void GpuPassTimer::collect() {
    context_.makeCurrent();
    for (Set& s : sets_) read(s);
}

void GpuPassTimer::beginFrame() {
    if (active_ >= 0) end();  // a frame that threw inside a pass
    ++frame_;
    collect();
    // The set of three frames back: results still unfinished now are dropped rather than waited for.
    Set& s = sets_[std::size_t(frame_ % kSets)];
    s.used.fill(false);
    s.frame = frame_;
}

void GpuPassTimer::begin(GpuPass pass) {
    if (active_ >= 0) throw std::logic_error("GpuPassTimer::begin: a pass is already being timed");
    Set& s = sets_[std::size_t(frame_ % kSets)];
    const std::size_t p = std::size_t(pass);
    if (frame_ < 0 || s.used[p]) throw std::logic_error("GpuPassTimer::begin: no frame begun, or the pass was timed already");
    context_.makeCurrent();
    context_.gl().BeginQuery(GL_TIME_ELAPSED, s.queries[p]);
    s.used[p] = true;
    active_ = int(p);
}

void GpuPassTimer::end() {
    if (active_ < 0) return;
    context_.makeCurrent();
    context_.gl().EndQuery(GL_TIME_ELAPSED);
    active_ = -1;
}

}  // namespace throng
