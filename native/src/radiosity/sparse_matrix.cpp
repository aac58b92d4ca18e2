#include "radiosity/sparse_matrix.h"

#include <utility>

namespace stratum {

SparseMatrix::SparseMatrix(const std::vector<uint32_t>& row_lengths, std::vector<SparseEntry> entries)
    : entries_(std::move(entries)) {
    begin_.resize(row_lengths.size() + 1);
    begin_[0] = 0;
    for (size_t i = 0; i < row_lengths.size(); ++i) begin_[i + 1] = begin_[i] + row_lengths[i];
}

SparseMatrix SparseMatrix::transposed() const {
    const uint32_t n = rows();
    std::vector<uint32_t> lengths(n, 0);
    for (const SparseEntry& e : entries_) ++lengths[e.column];
    SparseMatrix t;
    t.begin_.resize(static_cast<size_t>(n) + 1);
    t.begin_[0] = 0;
    for (uint32_t i = 0; i < n; ++i) t.begin_[i + 1] = t.begin_[i] + lengths[i];
    t.entries_.resize(entries_.size());
    // Rows in order: each transposed row receives its entries in increasing column order.
    std::vector<uint64_t> next(t.begin_.begin(), t.begin_.end() - 1);
    for (uint32_t i = 0; i < n; ++i)
        for (const SparseEntry& e : row(i)) t.entries_[next[e.column]++] = {i, e.value};
    return t;
}

}  // namespace stratum
