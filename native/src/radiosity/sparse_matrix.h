// A sparse matrix stored by rows (compressed sparse rows): the form factors G_ij of a patch i
// list only the patches its rays hit, so memory is the number of non-zero entries, never K².
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace stratum {

struct SparseEntry {
    uint32_t column;
    float value;
};

class SparseMatrix {
public:
    SparseMatrix() = default;
    // `row_lengths` entries per row, `entries` row after row.
    SparseMatrix(const std::vector<uint32_t>& row_lengths, std::vector<SparseEntry> entries);

    uint32_t rows() const { return static_cast<uint32_t>(begin_.empty() ? 0 : begin_.size() - 1); }
    size_t entries() const { return entries_.size(); }
    std::span<const SparseEntry> row(uint32_t i) const {
        return {entries_.data() + begin_[i], entries_.data() + begin_[i + 1]};
    }
    // The transpose (rows become columns) of a square matrix, each row's entries in column order.
    SparseMatrix transposed() const;
    size_t bytes() const {
        return begin_.capacity() * sizeof(uint64_t) + entries_.capacity() * sizeof(SparseEntry);
    }

private:
    std::vector<uint64_t> begin_;  // rows + 1 offsets into entries_
    std::vector<SparseEntry> entries_;
};

}  // namespace stratum
