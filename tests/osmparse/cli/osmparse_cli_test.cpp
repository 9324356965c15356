// Bad input to the osmparse binary: non-zero exit, exactly one line on stderr, an
// existing output file unchanged, and no partial or temporary file left beside it.
#include <gtest/gtest.h>

#include <filesystem>

#include "tests/test_support.h"

using namespace citygen::test;
namespace fs = std::filesystem;

namespace {

const std::string kPrevious = "previous contents, must survive a failed run\n";

class BadInput : public testing::Test {
protected:
    void SetUp() override { write_text(output(), kPrevious); }
    std::string output() const { return dir_.file("out.scene"); }

    // Runs osmparse with `args` (output -o out.scene appended unless given) and checks
    // every promise about failures.
    CommandResult expect_failure(const std::string& args, const std::string& message_part) {
        const CommandResult r = run_command(quoted(osmparse_binary()) + " " + args);
        EXPECT_NE(r.exit_code, 0) << args;
        EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << "stderr: " << r.err;
        EXPECT_EQ(r.err.rfind("osmparse: ", 0), 0u) << r.err;
        EXPECT_NE(r.err.find(message_part), std::string::npos) << "stderr: " << r.err;
        EXPECT_EQ(read_text(output()), kPrevious) << "existing output was touched";
        std::vector<std::string> left;
        for (const auto& entry : fs::directory_iterator(dir_.path())) left.push_back(entry.path().filename().string());
        std::sort(left.begin(), left.end());
        EXPECT_EQ(left, expected_files_) << "partial or temporary files left behind";
        return r;
    }
    std::string input(const std::string& name, const std::string& text) {
        write_text(dir_.file(name), text);
        expected_files_.push_back(name);
        std::sort(expected_files_.begin(), expected_files_.end());
        return dir_.file(name);
    }
    std::string out_arg() const { return " -o " + quoted(output()); }

    TempDir dir_;
    std::vector<std::string> expected_files_{"out.scene"};
};

std::string fixture(const std::string& name) { return quoted(source_path("tests/data/" + name + ".osm")); }

}  // namespace

TEST_F(BadInput, MissingFile) {
    expect_failure(quoted(dir_.file("nowhere.osm")) + out_arg(), "nowhere.osm: cannot open input");
}

TEST_F(BadInput, EmptyFile) {
    expect_failure(quoted(input("empty.osm", "")) + out_arg(), "empty.osm: empty file");
}

TEST_F(BadInput, Directory) {
    expect_failure(quoted(dir_.path()) + out_arg(), "is a directory");
}

TEST_F(BadInput, NotOsmXml) {
    expect_failure(quoted(input("page.osm", "<?xml version=\"1.0\"?>\n<html><body>hello</body></html>\n")) + out_arg(),
                   "page.osm: cannot read OSM data");
}

TEST_F(BadInput, NotXmlAtAll) {
    expect_failure(quoted(input("text.osm", "this is not xml\n")) + out_arg(), "text.osm: cannot read OSM data");
}

TEST_F(BadInput, TruncatedXml) {
    const std::string whole = read_text(source_path("tests/data/courtyard_multipolygon.osm"));
    expect_failure(quoted(input("cut.osm", whole.substr(0, whole.size() / 2))) + out_arg(),
                   "cut.osm: cannot read OSM data");
}

TEST_F(BadInput, GarbagePbf) {
    expect_failure(quoted(input("junk.osm.pbf", std::string(300, '\x7f'))) + out_arg(), "junk.osm.pbf");
}

TEST_F(BadInput, OutputDirectoryMissing) {
    expect_failure(fixture("clipped_way") + " -o " + quoted(dir_.file("no/such/dir/x.scene")), "cannot write");
}

TEST_F(BadInput, OutputParentIsAFile) {
    expect_failure(fixture("clipped_way") + " -o " + quoted(output() + "/x.scene"), "cannot write");
}

TEST_F(BadInput, OutputIsADirectory) {
    fs::create_directory(dir_.file("adir"));
    expected_files_ = {"adir", "out.scene"};
    expect_failure(fixture("clipped_way") + " -o " + quoted(dir_.file("adir")), "cannot write");
}

TEST_F(BadInput, AbsurdOptionValues) {
    expect_failure(fixture("clipped_way") + out_arg() + " --building-min-h -5", "--building-min-h");
    expect_failure(fixture("clipped_way") + out_arg() + " --building-max-h 1e9", "--building-max-h");
    expect_failure(fixture("clipped_way") + out_arg() + " --simplify-angle 400", "--simplify-angle");
    expect_failure(fixture("clipped_way") + out_arg() + " --seed many", "--seed");
    expect_failure(fixture("clipped_way") + out_arg() + " --building-min-h 50 --building-max-h 10",
                   "--building-min-h is larger than --building-max-h");
}

TEST_F(BadInput, NoOutputGiven) {
    expect_failure(fixture("clipped_way"), "-o");
}

TEST(GoodInput, WritesTheSceneAndReportsCounts) {
    TempDir dir;
    const CommandResult r = run_command(quoted(osmparse_binary()) + " " + fixture("building_with_parts") +
                                        " -o " + quoted(dir.file("ok.scene")));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.err.find("replaced by its building:part outlines"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("buildings"), std::string::npos);
    EXPECT_TRUE(fs::exists(dir.file("ok.scene")));
    const CommandResult info = run_command(quoted(osmparse_binary()) + " --info " + quoted(dir.file("ok.scene")));
    EXPECT_EQ(info.exit_code, 0);
    EXPECT_NE(info.out.find("building_parts: 2"), std::string::npos) << info.out;
    EXPECT_NE(info.out.find("building_heights: 6.0 - 30.0 m, median 12.0 m (1 from height, 2 from levels, 0 random)"),
              std::string::npos) << info.out;
}
