// BC6H tables (bc6h_tables.h), transcribed from KDFS table-bptcblockmodes and table-bptcblockformat. Each layout
// below is the spec's "Block description" row after the mode bits, one LayoutRun per element v^a..b: a >= b gives
// {v, b, a - b + 1, forward}, a < b (the reversed high bits of modes 11 and 15) gives {v, b, b - a + 1, reversed}.
// tests/unit/test_bc6h_block.cpp checks that every mode's runs fill exactly bits 0..81 (two subsets) or 0..64 (one
// subset) and give each endpoint field exactly its EPB or delta bits; the reference decoder
// (bc6h_reference_decode.cpp) reads the same spec rows from its own text transcription.
#include "formats/bc6h/bc6h_tables.h"

#include <string>

#include "core/error.h"

namespace blocklab {
namespace bc6h {

namespace {

enum Field : std::uint8_t { R0, G0, B0, R1, G1, B1, R2, G2, B2, R3, G3, B3, PB };

constexpr LayoutRun run(Field field, int high, int low) {   // v^high..low, high >= low
  return {field, static_cast<std::uint8_t>(low), static_cast<std::uint8_t>(high - low + 1), false};
}
constexpr LayoutRun bit(Field field, int position) { return run(field, position, position); }
constexpr LayoutRun reversed(Field field, int low, int high) {   // v^low..high: first block bit -> bit high
  return {field, static_cast<std::uint8_t>(high), static_cast<std::uint8_t>(high - low + 1), true};
}

constexpr LayoutRun kMode0[] = {
    bit(G2, 4),     bit(B2, 4),     bit(B3, 4),   run(R0, 9, 0),  run(G0, 9, 0),  run(B0, 9, 0),  run(R1, 4, 0),
    bit(G3, 4),     run(G2, 3, 0),  run(G1, 4, 0), bit(B3, 0),    run(G3, 3, 0),  run(B1, 4, 0),  bit(B3, 1),
    run(B2, 3, 0),  run(R2, 4, 0),  bit(B3, 2),   run(R3, 4, 0),  bit(B3, 3),     run(PB, 4, 0)};
constexpr LayoutRun kMode1[] = {
    bit(G2, 5),     bit(G3, 4),     bit(G3, 5),   run(R0, 6, 0),  bit(B3, 0),     bit(B3, 1),     bit(B2, 4),
    run(G0, 6, 0),  bit(B2, 5),     bit(B3, 2),   bit(G2, 4),     run(B0, 6, 0),  bit(B3, 3),     bit(B3, 5),
    bit(B3, 4),     run(R1, 5, 0),  run(G2, 3, 0), run(G1, 5, 0), run(G3, 3, 0),  run(B1, 5, 0),  run(B2, 3, 0),
    run(R2, 5, 0),  run(R3, 5, 0),  run(PB, 4, 0)};
constexpr LayoutRun kMode2[] = {
    run(R0, 9, 0),  run(G0, 9, 0),  run(B0, 9, 0), run(R1, 4, 0), bit(R0, 10),    run(G2, 3, 0),  run(G1, 3, 0),
    bit(G0, 10),    bit(B3, 0),     run(G3, 3, 0), run(B1, 3, 0), bit(B0, 10),    bit(B3, 1),     run(B2, 3, 0),
    run(R2, 4, 0),  bit(B3, 2),     run(R3, 4, 0), bit(B3, 3),    run(PB, 4, 0)};
constexpr LayoutRun kMode6[] = {
    run(R0, 9, 0),  run(G0, 9, 0),  run(B0, 9, 0), run(R1, 3, 0), bit(R0, 10),    bit(G3, 4),     run(G2, 3, 0),
    run(G1, 4, 0),  bit(G0, 10),    run(G3, 3, 0), run(B1, 3, 0), bit(B0, 10),    bit(B3, 1),     run(B2, 3, 0),
    run(R2, 3, 0),  bit(B3, 0),     bit(B3, 2),   run(R3, 3, 0),  bit(G2, 4),     bit(B3, 3),     run(PB, 4, 0)};
constexpr LayoutRun kMode10[] = {
    run(R0, 9, 0),  run(G0, 9, 0),  run(B0, 9, 0), run(R1, 3, 0), bit(R0, 10),    bit(B2, 4),     run(G2, 3, 0),
    run(G1, 3, 0),  bit(G0, 10),    bit(B3, 0),   run(G3, 3, 0),  run(B1, 4, 0),  bit(B0, 10),    run(B2, 3, 0),
    run(R2, 3, 0),  bit(B3, 1),     bit(B3, 2),   run(R3, 3, 0),  bit(B3, 4),     bit(B3, 3),     run(PB, 4, 0)};
constexpr LayoutRun kMode14[] = {
    run(R0, 8, 0),  bit(B2, 4),     run(G0, 8, 0), bit(G2, 4),    run(B0, 8, 0),  bit(B3, 4),     run(R1, 4, 0),
    bit(G3, 4),     run(G2, 3, 0),  run(G1, 4, 0), bit(B3, 0),    run(G3, 3, 0),  run(B1, 4, 0),  bit(B3, 1),
    run(B2, 3, 0),  run(R2, 4, 0),  bit(B3, 2),   run(R3, 4, 0),  bit(B3, 3),     run(PB, 4, 0)};
constexpr LayoutRun kMode18[] = {
    run(R0, 7, 0),  bit(G3, 4),     bit(B2, 4),   run(G0, 7, 0),  bit(B3, 2),     bit(G2, 4),     run(B0, 7, 0),
    bit(B3, 3),     bit(B3, 4),     run(R1, 5, 0), run(G2, 3, 0), run(G1, 4, 0),  bit(B3, 0),     run(G3, 3, 0),
    run(B1, 4, 0),  bit(B3, 1),     run(B2, 3, 0), run(R2, 5, 0), run(R3, 5, 0),  run(PB, 4, 0)};
constexpr LayoutRun kMode22[] = {
    run(R0, 7, 0),  bit(B3, 0),     bit(B2, 4),   run(G0, 7, 0),  bit(G2, 5),     bit(G2, 4),     run(B0, 7, 0),
    bit(G3, 5),     bit(B3, 4),     run(R1, 4, 0), bit(G3, 4),    run(G2, 3, 0),  run(G1, 5, 0),  run(G3, 3, 0),
    run(B1, 4, 0),  bit(B3, 1),     run(B2, 3, 0), run(R2, 4, 0), bit(B3, 2),     run(R3, 4, 0),  bit(B3, 3),
    run(PB, 4, 0)};
constexpr LayoutRun kMode26[] = {
    run(R0, 7, 0),  bit(B3, 1),     bit(B2, 4),   run(G0, 7, 0),  bit(B2, 5),     bit(G2, 4),     run(B0, 7, 0),
    bit(B3, 5),     bit(B3, 4),     run(R1, 4, 0), bit(G3, 4),    run(G2, 3, 0),  run(G1, 4, 0),  bit(B3, 0),
    run(G3, 3, 0),  run(B1, 5, 0),  run(B2, 3, 0), run(R2, 4, 0), bit(B3, 2),     run(R3, 4, 0),  bit(B3, 3),
    run(PB, 4, 0)};
constexpr LayoutRun kMode30[] = {
    run(R0, 5, 0),  bit(G3, 4),     bit(B3, 0),   bit(B3, 1),     bit(B2, 4),     run(G0, 5, 0),  bit(G2, 5),
    bit(B2, 5),     bit(B3, 2),     bit(G2, 4),   run(B0, 5, 0),  bit(G3, 5),     bit(B3, 3),     bit(B3, 5),
    bit(B3, 4),     run(R1, 5, 0),  run(G2, 3, 0), run(G1, 5, 0), run(G3, 3, 0),  run(B1, 5, 0),  run(B2, 3, 0),
    run(R2, 5, 0),  run(R3, 5, 0),  run(PB, 4, 0)};
constexpr LayoutRun kMode3[] = {run(R0, 9, 0), run(G0, 9, 0), run(B0, 9, 0),
                                run(R1, 9, 0), run(G1, 9, 0), run(B1, 9, 0)};
constexpr LayoutRun kMode7[] = {run(R0, 9, 0), run(G0, 9, 0), run(B0, 9, 0), run(R1, 8, 0), bit(R0, 10),
                                run(G1, 8, 0), bit(G0, 10),   run(B1, 8, 0), bit(B0, 10)};
constexpr LayoutRun kMode11[] = {run(R0, 9, 0),      run(G0, 9, 0), run(B0, 9, 0),      run(R1, 7, 0),
                                 reversed(R0, 10, 11), run(G1, 7, 0), reversed(G0, 10, 11), run(B1, 7, 0),
                                 reversed(B0, 10, 11)};
constexpr LayoutRun kMode15[] = {run(R0, 9, 0),      run(G0, 9, 0), run(B0, 9, 0),      run(R1, 3, 0),
                                 reversed(R0, 10, 15), run(G1, 3, 0), reversed(G0, 10, 15), run(B1, 3, 0),
                                 reversed(B0, 10, 15)};

template <std::size_t N>
constexpr int count_of(const LayoutRun (&)[N]) {
  return static_cast<int>(N);
}

#define BC6H_RUNS(table) table, count_of(table)
const ModeInfo kModes[kModeCount] = {
    {0, 2, 2, true, 10, {5, 5, 5}, BC6H_RUNS(kMode0)},     {1, 2, 2, true, 7, {6, 6, 6}, BC6H_RUNS(kMode1)},
    {2, 5, 2, true, 11, {5, 4, 4}, BC6H_RUNS(kMode2)},     {6, 5, 2, true, 11, {4, 5, 4}, BC6H_RUNS(kMode6)},
    {10, 5, 2, true, 11, {4, 4, 5}, BC6H_RUNS(kMode10)},   {14, 5, 2, true, 9, {5, 5, 5}, BC6H_RUNS(kMode14)},
    {18, 5, 2, true, 8, {6, 5, 5}, BC6H_RUNS(kMode18)},    {22, 5, 2, true, 8, {5, 6, 5}, BC6H_RUNS(kMode22)},
    {26, 5, 2, true, 8, {5, 5, 6}, BC6H_RUNS(kMode26)},    {30, 5, 2, false, 6, {6, 6, 6}, BC6H_RUNS(kMode30)},
    {3, 5, 1, false, 10, {10, 10, 10}, BC6H_RUNS(kMode3)}, {7, 5, 1, true, 11, {9, 9, 9}, BC6H_RUNS(kMode7)},
    {11, 5, 1, true, 12, {8, 8, 8}, BC6H_RUNS(kMode11)},   {15, 5, 1, true, 16, {4, 4, 4}, BC6H_RUNS(kMode15)},
};
#undef BC6H_RUNS

}  // namespace

const ModeInfo& mode_info(int mode_index) {
  if (mode_index < 0 || mode_index >= kModeCount)
    fail("bc6h::mode_info", "mode index " + std::to_string(mode_index) + " is outside 0..13");
  return kModes[mode_index];
}

int mode_index_of_number(int mode_number) {
  for (int index = 0; index < kModeCount; ++index)
    if (kModes[index].mode_number == mode_number) return index;
  return kReservedModeIndex;
}

int mode_index_of_block(const std::uint8_t* bytes) {
  const int low_two = bytes[0] & 3;
  return mode_index_of_number(low_two < 2 ? low_two : (bytes[0] & 31));
}

}  // namespace bc6h
}  // namespace blocklab
