// bmfr.Sequence: the frames of a sequence folder (either layout) as dicts of arrays, loaded one
// at a time; iterable, indexable (negative indices count from the end) and sliceable (a slice
// is a Sequence over those frames).
#pragma once
#include "io/sequence.h"
#include <memory>
#include <pybind11/pybind11.h>
#include <vector>

namespace bmfr::python {

namespace py = pybind11;

class Sequence {
  public:
    Sequence(const std::string& path, const std::map<std::string, std::string>& layers);
    /// Frame `index` of the folder as a dict: the buffers by their input_buffers() names,
    /// reference, extras, view_projection, jitter, reset and index.
    py::dict frame(int index) const;
    py::object item(const py::object& key) const; ///< an int or a slice
    int size() const { return int(indices_.size()); }
    int indexAt(int position) const { return indices_[size_t(position)]; }
    py::dict info() const;
    std::vector<std::string> notes() const { return reader_->notes(); }
    /// What `bmfr denoise` takes from the sequence, as Filter keywords: its own discard limits
    /// and whether its colour is demodulated.
    py::dict settings() const;
    std::string repr() const;

  private:
    Sequence(std::shared_ptr<SequenceReader> reader, std::vector<int> indices)
        : reader_(std::move(reader)), indices_(std::move(indices)) {}
    std::shared_ptr<SequenceReader> reader_;
    std::vector<int> indices_; ///< the folder's frame indices this sequence holds, in order
};

/// Iterates a Sequence (one pass; a new one per iter()).
class SequenceIterator {
  public:
    explicit SequenceIterator(const Sequence& s) : sequence_(s) {}
    py::dict next();

  private:
    Sequence sequence_;
    int position_ = 0;
};

/// The module's Sequence, read_sequence and Sequence's iterator.
void bindSequence(py::module_& m);

} // namespace bmfr::python
