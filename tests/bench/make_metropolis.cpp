// make_metropolis: a benchmark input, not a test fixture (issue 25). Tiles a real OSM extract
// N x N: tile (i, j) is the extract shifted east by i and north by j times its own extent in
// degrees, every object with a fresh id (id + tile * (largest id of its type + 1)) and every
// reference moved with it, so the copies are separate objects that abut like city districts.
//
//   build/bin/make_metropolis CITY.osm[.pbf|.gz|.bz2] N OUT.osm.pbf
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>
#include <string>

#include <osmium/io/any_input.hpp>
#include <osmium/io/any_output.hpp>
#include <osmium/memory/buffer.hpp>
#include <osmium/osm.hpp>

namespace {

struct Extent {
    osmium::object_id_type largest[3] = {0, 0, 0};  // node, way, relation
    osmium::Box box;
};

int type_index(osmium::item_type type) {
    return type == osmium::item_type::node ? 0 : type == osmium::item_type::way ? 1 : 2;
}

Extent measure(const osmium::memory::Buffer& input) {
    Extent e;
    for (const auto& object : input.select<osmium::OSMObject>()) {
        auto& largest = e.largest[type_index(object.type())];
        largest = std::max(largest, std::abs(object.id()));
        if (object.type() == osmium::item_type::node) {
            const auto& node = static_cast<const osmium::Node&>(object);
            if (node.location().valid()) e.box.extend(node.location());
        }
    }
    return e;
}

osmium::object_id_type moved(osmium::object_id_type id, osmium::object_id_type offset) {
    return id >= 0 ? id + offset : id - offset;
}

// The objects of one type of tile k, shifted by (dlon, dlat) degrees.
void add_tile(const osmium::memory::Buffer& input, const Extent& e, osmium::item_type type, int k, double dlon,
              double dlat, osmium::memory::Buffer& out) {
    osmium::object_id_type offset[3];
    for (int t = 0; t < 3; ++t) offset[t] = static_cast<osmium::object_id_type>(k) * (e.largest[t] + 1);
    for (const auto& object : input.select<osmium::OSMObject>()) {
        if (object.type() != type) continue;
        auto& copy = out.add_item(object);
        copy.set_id(moved(object.id(), offset[type_index(type)]));
        if (type == osmium::item_type::node) {
            auto& node = static_cast<osmium::Node&>(copy);
            const osmium::Location at = node.location();
            if (at.valid()) node.set_location(osmium::Location{at.lon() + dlon, at.lat() + dlat});
        } else if (type == osmium::item_type::way) {
            for (auto& ref : static_cast<osmium::Way&>(copy).nodes()) ref.set_ref(moved(ref.ref(), offset[0]));
        } else {
            for (auto& member : static_cast<osmium::Relation&>(copy).members())
                member.set_ref(moved(member.ref(), offset[type_index(member.type())]));
        }
        out.commit();
    }
}

}  // namespace

int main(int argc, char** argv) {
    if (argc != 4) {
        std::fprintf(stderr, "usage: make_metropolis CITY.osm N OUT.osm.pbf\n");
        return 2;
    }
    const int n = std::atoi(argv[2]);
    if (n < 1 || n > 32) {
        std::fprintf(stderr, "make_metropolis: N must be 1-32, got '%s'\n", argv[2]);
        return 2;
    }
    try {
        osmium::io::Reader reader{argv[1]};
        osmium::io::Header header = reader.header();
        osmium::memory::Buffer input{1024 * 1024, osmium::memory::Buffer::auto_grow::yes};
        while (osmium::memory::Buffer chunk = reader.read()) input.add_buffer(chunk), input.commit();
        reader.close();
        const Extent e = measure(input);
        if (!e.box.valid()) throw std::runtime_error("no node has a location");
        const double dlon = e.box.top_right().lon() - e.box.bottom_left().lon();
        const double dlat = e.box.top_right().lat() - e.box.bottom_left().lat();
        osmium::Box all = e.box;
        all.extend(osmium::Location{e.box.top_right().lon() + (n - 1) * dlon, e.box.top_right().lat() + (n - 1) * dlat});
        header.boxes().clear();
        header.add_box(all);
        header.set("generator", "citygen make_metropolis");
        osmium::io::Writer writer{argv[3], header, osmium::io::overwrite::allow};
        // Nodes of every tile first, then ways, then relations: the order PBF readers expect.
        for (osmium::item_type type : {osmium::item_type::node, osmium::item_type::way, osmium::item_type::relation})
            for (int k = 0; k < n * n; ++k) {
                osmium::memory::Buffer out{input.committed() + 1024, osmium::memory::Buffer::auto_grow::yes};
                add_tile(input, e, type, k, (k % n) * dlon, (k / n) * dlat, out);
                writer(std::move(out));
            }
        writer.close();
    } catch (const std::exception& error) {
        std::fprintf(stderr, "make_metropolis: %s\n", error.what());
        return 1;
    }
    return 0;
}
