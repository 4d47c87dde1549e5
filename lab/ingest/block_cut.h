// SPDX-License-Identifier: MIT
// Block cut -> mixing grids C and S per case (thesis ch. 3, eqs 3.1-3.8, Table 3.2).
//
// After hardening, each mixing box is cut into 4 x 3 x 3 blocks: i = 1..4 along the 20 cm side (5 cm blocks),
// j = 1..3 along the 16.5 cm side (5.5 cm), layer k = 1..3 from the top (3 cm). Block id "M_ijk" must agree
// with the i, j, layer columns. Per block, from the dried masses M_wr (rock) and M_p (paste):
//   C = M_wr / (M_wr + M_p)                                                 (3.1)
//   S = V_paste.dried / V_voids = M_p K / (rho_s (1 - e_f/(1 + e_f)) M_wr)     (3.8), K = rho_wr / n_wr
// K is an INPUT: the thesis never states rho_wr or n_wr; 3570 (cases 2-3) and 3488 kg/m3 (cases 4-5) are
// back-calculated from its printed S (datasets/thesis/README.md). Without K for a case, S is not computed.
// S is capped at 1 (voids full; the excess is unmixed paste inside the block) and flagged; it is undefined
// without rock (M_wr = 0). Grids are stored row-major as [i][j][k] (dims 4 x 3 x 3), k = 1 the top layer.
#pragma once

#include <array>
#include <cstdint>
#include <limits>
#include <map>
#include <string>
#include <vector>

#include "base/csv.h"
#include "lab/ingest/ingest.h"

namespace pastemix::lab {

inline constexpr int kBlocksI = 4, kBlocksJ = 3, kLayers = 3;
inline constexpr int kBlocks = kBlocksI * kBlocksJ * kLayers;
// Index of block (i, j, k), all 1-based, in the row-major [i][j][k] grid.
inline int block_index(int i, int j, int k) { return ((i - 1) * kBlocksJ + (j - 1)) * kLayers + (k - 1); }

// Why a block's S is what it is. Stored as int32 in lab.h5.
enum class SFlag : std::int32_t {
  value = 0,    // S computed, <= 1
  capped = 1,   // eq. 3.8 gave more than 1; S set to 1, the raw value kept in S_raw
  no_rock = 2,  // M_wr = 0: no voids to fill, S undefined (NaN)
  no_K = 3,     // K unknown for this case: S not computed (NaN)
};
const char* to_string(SFlag f);

struct BlockGrid {
  static constexpr double nan = std::numeric_limits<double>::quiet_NaN();
  int case_id = 0;
  double K = nan;        // kg/m3, rho_wr / n_wr; NaN if unknown
  std::string K_source;  // where K came from
  std::array<double, kBlocks> M_wr{}, M_paste{};  // kg, dried
  std::array<double, kBlocks> rho_s{}, e_f{};     // kg/m3 and -, per block as in the file
  std::array<double, kBlocks> C{}, S{}, S_raw{};  // fractions (0..1); S capped, S_raw not
  std::array<std::int32_t, kBlocks> flag{};       // SFlag
  std::array<std::int32_t, kBlocks> corrected{};  // 1 where the Table 3.3 correction was applied
  std::array<int, kBlocks> line{};                // source line of each block
  std::array<double, kBlocks> C_printed{}, S_printed{};  // fractions as printed; NaN if empty
};

// C, S_raw, S and flag of block b from its masses, rho_s, e_f and the grid's K.
void compute_block(BlockGrid& g, int b);

struct BlockCutComparison {
  int n_C = 0;                 // blocks with a printed C
  double max_C_error_pp = 0;   // max |C - printed| in percentage points
  int n_S = 0;                 // printed finite S that we computed (compared against S_raw)
  double max_S_rel_error = 0;  // max relative |S_raw - printed| / printed
  int n_capped = 0;            // blocks we capped
  int n_flag_disagreements = 0;
};

struct BlockCutResult {
  std::vector<BlockGrid> cases;      // Table 3.2 as measured, ascending case
  std::vector<BlockGrid> corrected;  // the same cases with Table 3.3 applied; empty without corrections
  BlockCutComparison printed, printed_corrected;
  std::vector<Parameter> parameters;  // block_cut.case_N.K (the inputs, with their source)
  std::vector<Warning> warnings;
};

struct KInput {
  double value = 0.0;  // kg/m3
  std::string source;  // provenance text
};

const std::vector<ColumnSpec>& block_cut_columns();
// Columns: case, block_id, i, j, layer, M_wr_kg, M_paste_dried_kg, rho_s_kg_m3, e_f, and optionally the
// printed C_percent, S_percent, S_flag. Every case present must have its 36 blocks, once each.
BlockCutResult ingest_block_cut(const CsvTable& table, const ColumnUnits& units, const std::map<int, KInput>& K);

}  // namespace pastemix::lab
