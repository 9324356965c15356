// Writes an SRTM3 tile of made-up rolling ground for the farm test (tests/farm/parse_farm_test.sh):
// 1201 x 1201 big-endian int16 metres, 3 arc-seconds apart, rows north to south; the tile's
// place is in its file name (e.g. N52E013.hgt), which the caller chooses.
//   write_srtm_tile OUT.hgt
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <string>

int main(int argc, char** argv) {
    if (argc != 2) {
        std::fprintf(stderr, "usage: write_srtm_tile OUT.hgt\n");
        return 2;
    }
    std::string bytes;
    for (int row = 0; row < 1201; ++row) {
        for (int col = 0; col < 1201; ++col) {
            // Hills a few hundred metres across, rising to the north: every tile of a region cut
            // a few kilometres wide has its own lowest point.
            const double h = 60 + 0.05 * (1200 - row) + 12 * std::sin(col / 9.0) + 8 * std::cos(row / 7.0);
            const auto v = static_cast<uint16_t>(static_cast<int16_t>(std::lround(h)));
            bytes.push_back(static_cast<char>(v >> 8));
            bytes.push_back(static_cast<char>(v & 0xff));
        }
    }
    std::FILE* out = std::fopen(argv[1], "wb");
    if (!out || std::fwrite(bytes.data(), 1, bytes.size(), out) != bytes.size() || std::fclose(out) != 0) {
        std::fprintf(stderr, "write_srtm_tile: cannot write %s\n", argv[1]);
        return 1;
    }
    return 0;
}
