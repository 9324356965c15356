#include "osmparse/roofs/wavefront_skeleton.h"

#include <algorithm>
#include <cmath>

namespace citygen {

namespace {

// Every event scans the whole wavefront (n^3 in all): beyond this many points CGAL is faster.
constexpr size_t kMaxPoints = 256;
// Events closer in time than this (metres of offset) are too close to order in doubles.
constexpr double kTimeTie = 1e-7;
// Relative to the footprint's size: simultaneous events closer than this may interact.
constexpr double kApart = 1e-4;
// Relative to the footprint's size: a reflex vertex reaching an edge this near its end hits
// the vertex there (a vertex event).
constexpr double kOnVertex = 1e-6;

struct Edge {
    Vec2 dir;     // unit, along the footprint edge
    Vec2 normal;  // unit, pointing inside
    double c;     // dot(normal, p) + c = distance of p inside the edge's line
};

struct Vertex {
    Vec2 p0;       // position at time t0
    double t0;
    Vec2 velocity;  // per unit of time: stays on the offset lines of edges in and out
    int in, out;    // edges before and after it (counter-clockwise)
    int prev, next;
    bool alive;
    bool reflex;
    Vec2 at(double t) const { return p0 + velocity * (t - t0); }
};

struct Node {
    Vec2 p;
    double t;
};

class Wavefront {
public:
    Wavefront(const Ring& ring, double scale) : scale_(scale) {
        const int n = static_cast<int>(ring.size());
        for (int i = 0; i < n; ++i) {
            const Vec2 a = ring[i], b = ring[(i + 1) % n];
            Edge e;
            e.dir = normalize(b - a);
            e.normal = perp_left(e.dir);
            e.c = -dot(e.normal, a);
            edges_.push_back(e);
        }
        face_nodes_.resize(n);
        for (int i = 0; i < n; ++i) add_node(ring[i], 0);  // node i is footprint vertex i
        for (int i = 0; i < n; ++i) face_nodes_[i] = {i, (i + 1) % n};
        for (int i = 0; i < n; ++i) {
            vertices_.push_back(vertex(ring[i], 0, (i + n - 1) % n, i, (i + n - 1) % n, (i + 1) % n));
            if (!set_velocity(vertices_.back())) ok_ = false;
        }
    }

    // Runs every event; false when one cannot be decided in doubles.
    bool run() {
        for (size_t step = 0; ok_ && step < 8 * edges_.size() + 16; ++step) {
            int alive = 0;
            for (const Vertex& v : vertices_) alive += v.alive;
            if (alive == 0) return true;
            if (!next_event()) return false;
        }
        return false;
    }

    // Nodes of each edge's face: the edge's two ends first, then the skeleton nodes it reached.
    const std::vector<std::vector<int>>& face_nodes() const { return face_nodes_; }
    const std::vector<Node>& nodes() const { return nodes_; }
    const std::vector<Edge>& edges() const { return edges_; }

private:
    static Vertex vertex(Vec2 p, double t, int in, int out, int prev, int next) {
        Vertex v;
        v.p0 = p;
        v.t0 = t;
        v.in = in;
        v.out = out;
        v.prev = prev;
        v.next = next;
        v.alive = true;
        v.reflex = false;
        return v;
    }
    int add_node(Vec2 p, double t) {
        nodes_.push_back({p, t});
        return static_cast<int>(nodes_.size()) - 1;
    }
    bool set_velocity(Vertex& v) const {
        const Vec2 a = edges_[v.in].normal, b = edges_[v.out].normal;
        const double det = cross(a, b);
        // Parallel edges meet nowhere (or everywhere): leave it to exact arithmetic.
        if (std::fabs(det) < 1e-9) return false;
        v.velocity = {(b.y - a.y) / det, (a.x - b.x) / det};
        v.reflex = cross(edges_[v.in].dir, edges_[v.out].dir) < 0;
        return true;
    }

    enum class Kind { None, Collapse, Split };
    struct Event {
        Kind kind = Kind::None;
        double t = 0;
        Vec2 p;
        int v = -1;  // Collapse: the vertex at the start of the collapsing edge; Split: the reflex vertex
        int a = -1;  // Split: the vertex at the start of the edge it hits
        bool vertex_event = false;
    };

    // The earliest event over the whole wavefront; false when two come (nearly) together.
    bool next_event() {
        std::vector<Event> events;
        auto offer = [&](const Event& e) { events.push_back(e); };
        for (int i = 0; i < static_cast<int>(vertices_.size()); ++i) {
            const Vertex& u = vertices_[i];
            if (!u.alive) continue;
            // The edge from u to its next vertex shrinks to nothing.
            const Vertex& w = vertices_[u.next];
            // A triangle's three edges vanish together in one point: one event for it.
            if (vertices_[w.next].next == i && (u.next < i || w.next < i)) continue;
            const Vec2 dir = edges_[u.out].dir;
            const double a = dot(w.p0 - w.velocity * w.t0 - (u.p0 - u.velocity * u.t0), dir);
            const double b = dot(w.velocity - u.velocity, dir);
            if (b < 0) {
                Event e;
                e.kind = Kind::Collapse;
                e.t = -a / b;
                e.p = (u.at(e.t) + w.at(e.t)) * 0.5;
                e.v = i;
                offer(e);
            }
            if (!u.reflex) continue;
            // The reflex vertex u runs into another edge of its own wavefront.
            for (int k = u.next; k != i; k = vertices_[k].next) {
                const Vertex& a_vertex = vertices_[k];
                const int edge = a_vertex.out;
                const int b_index = a_vertex.next;
                // Edges next but one: reaching them is the collapse of the edge between.
                if (edge == u.in || edge == u.out || k == i || b_index == i) continue;
                if (edge == vertices_[u.prev].in || edge == vertices_[u.next].out) continue;
                const Edge& e = edges_[edge];
                const double rate = 1 - dot(e.normal, u.velocity);
                if (!(rate > 1e-12)) continue;
                const double t = (dot(e.normal, u.p0) - dot(e.normal, u.velocity) * u.t0 + e.c) / rate;
                if (!(t > now_ - kTimeTie)) continue;
                const Vec2 x = u.at(t);
                const double s = dot(x, e.dir), sa = dot(a_vertex.at(t), e.dir), sb = dot(vertices_[b_index].at(t), e.dir);
                const double margin = kOnVertex * scale_;
                if (s < sa - margin || s > sb + margin) continue;
                Event ev;
                ev.kind = Kind::Split;
                // Onto a wavefront vertex (a vertex event): fatal only if it comes first.
                ev.vertex_event = s < sa + margin || s > sb - margin;
                ev.t = t;
                ev.p = x;
                ev.v = i;
                ev.a = k;
                offer(ev);
            }
        }
        if (events.empty()) return false;
        size_t first = 0;  // the earliest; the first found of equal times
        for (size_t k = 1; k < events.size(); ++k)
            if (events[k].t < events[first].t) first = k;
        const Event best = events[first];
        if (!(best.t > now_ - kTimeTie) || !std::isfinite(best.t)) return false;
        if (best.vertex_event) return false;
        // Simultaneous events far apart are independent (all events are found again after
        // each); at one place their order would decide the skeleton's shape. Every event within
        // the tie counts, not only the second earliest: a far one may come between two at one place.
        for (size_t k = 0; k < events.size(); ++k) {
            if (k == first || !(events[k].t < best.t + kTimeTie)) continue;
            if (events[k].vertex_event || length(events[k].p - best.p) < kApart * scale_) return false;
        }
        now_ = std::max(now_, best.t);
        return best.kind == Kind::Collapse ? collapse(best) : split(best);
    }

    int ring_size(int start) const {
        int n = 1;
        for (int k = vertices_[start].next; k != start && n < 100000; k = vertices_[k].next) ++n;
        return n;
    }

    bool collapse(const Event& ev) {
        Vertex& u = vertices_[ev.v];
        Vertex& w = vertices_[u.next];
        if (ring_size(ev.v) == 3) {  // the last triangle of this wavefront closes in one point
            Vertex& z = vertices_[w.next];
            if (length(z.at(ev.t) - ev.p) > 1e-6 * scale_) return false;
            const int node = add_node(ev.p, ev.t);
            for (int e : {u.in, u.out, w.out}) face_nodes_[e].push_back(node);
            u.alive = w.alive = z.alive = false;
            return true;
        }
        const int node = add_node(ev.p, ev.t);
        for (int e : {u.in, u.out, w.out}) face_nodes_[e].push_back(node);
        Vertex v = vertex(ev.p, ev.t, u.in, w.out, u.prev, w.next);
        if (!set_velocity(v)) return false;
        u.alive = w.alive = false;
        const int id = static_cast<int>(vertices_.size());
        vertices_[v.prev].next = id;
        vertices_[v.next].prev = id;
        vertices_.push_back(v);
        return true;
    }

    bool split(const Event& ev) {
        const Vertex v = vertices_[ev.v];
        const int a = ev.a, b = vertices_[a].next;
        const int edge = vertices_[a].out;
        const int node = add_node(ev.p, ev.t);
        for (int e : {v.in, v.out, edge}) face_nodes_[e].push_back(node);
        Vertex v1 = vertex(ev.p, ev.t, v.in, edge, v.prev, b);
        Vertex v2 = vertex(ev.p, ev.t, edge, v.out, a, v.next);
        if (!set_velocity(v1) || !set_velocity(v2)) return false;
        vertices_[ev.v].alive = false;
        const int id1 = static_cast<int>(vertices_.size()), id2 = id1 + 1;
        vertices_.push_back(v1);
        vertices_.push_back(v2);
        vertices_[v1.prev].next = id1;
        vertices_[b].prev = id1;
        vertices_[a].next = id2;
        vertices_[v2.next].prev = id2;
        return ring_size(id1) >= 3 && ring_size(id2) >= 3;
    }

    double scale_;
    double now_ = 0;
    bool ok_ = true;
    std::vector<Edge> edges_;
    std::vector<Vertex> vertices_;
    std::vector<Node> nodes_;
    std::vector<std::vector<int>> face_nodes_;
};

}  // namespace

bool wavefront_skeleton_faces(const Ring& outer, std::vector<SkeletonFace>* faces_out) {
    faces_out->clear();
    std::vector<SkeletonFace> faces;  // moved to faces_out only on success, as promised
    const size_t n = outer.size();
    if (n < 4 || n > kMaxPoints || !(signed_area(outer) > 0)) return false;
    // Relative to the first point, as CGAL is given it (roof_skeleton.cpp): the same digits.
    const Vec2 origin = outer[0];
    Ring ring;
    double scale = 0;
    for (Vec2 p : outer) {
        ring.push_back(p - origin);
        scale = std::max(scale, length(p - origin));
    }
    for (size_t i = 0; i < n; ++i)
        if (!(length(ring[(i + 1) % n] - ring[i]) > 1e-6)) return false;
    Wavefront front(ring, scale);
    if (!front.run()) return false;
    double area = 0;
    for (size_t i = 0; i < n; ++i) {
        const Edge& edge = front.edges()[i];
        std::vector<int> ids = front.face_nodes()[i];
        // ids[0] and ids[1] are the edge's start and end; the rest rise from end back to start.
        std::vector<int> upper(ids.begin() + 2, ids.end());
        std::sort(upper.begin(), upper.end());
        upper.erase(std::unique(upper.begin(), upper.end()), upper.end());
        auto along = [&](int id) { return dot(front.nodes()[id].p, edge.dir); };
        std::sort(upper.begin(), upper.end(), [&](int x, int y) { return along(x) > along(y); });
        // A face is monotone along its edge: nodes at one position along it cannot be ordered.
        for (size_t k = 0; k + 1 < upper.size(); ++k)
            if (along(upper[k]) - along(upper[k + 1]) < 1e-7 * scale) return false;
        if (upper.empty()) return false;
        // Starting at the edge's end, as CGAL's faces do.
        SkeletonFace face;
        std::vector<int> order{ids[1]};
        order.insert(order.end(), upper.begin(), upper.end());
        order.push_back(ids[0]);
        for (int id : order) {
            face.points.push_back(front.nodes()[id].p + origin);
            face.times.push_back(front.nodes()[id].t);
        }
        Ring flat;
        for (int id : order) flat.push_back(front.nodes()[id].p);
        const double a = signed_area(flat);
        if (!(a > 0)) return false;
        area += a;
        faces.push_back(std::move(face));
    }
    if (std::fabs(area - signed_area(ring)) > 1e-7 * std::fabs(signed_area(ring))) return false;
    // CGAL lists the last edge's face first.
    std::rotate(faces.begin(), faces.end() - 1, faces.end());
    *faces_out = std::move(faces);
    return true;
}

}  // namespace citygen
