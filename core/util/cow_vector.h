// A vector whose copies share storage: elements live in fixed-size chunks held by shared pointers, a copy
// copies the chunk pointers only, and a write copies the one chunk it touches first. ipd-studio publishes a
// copy of its whole Session after every edit; with 10,000 scenes per domain pair a deep copy costs more than
// the edit, while this costs one pointer per chunk plus the chunk the edit changed.
//
// A chunk is never changed once a vector holds it (writes go to a fresh copy), so copies may be read from
// any thread while the original is edited on another.
#pragma once

#include <cstddef>
#include <iterator>
#include <memory>
#include <stdexcept>
#include <utility>
#include <vector>

namespace ipd {

template <class T, size_t kChunk = 128>
class CowVector {
  using Chunk = std::vector<T>;

 public:
  class const_iterator {
   public:
    using iterator_category = std::random_access_iterator_tag;
    using value_type = T;
    using difference_type = std::ptrdiff_t;
    using pointer = const T*;
    using reference = const T&;
    const_iterator(const CowVector* v, size_t i) : v_(v), i_(i) {}
    reference operator*() const { return (*v_)[i_]; }
    pointer operator->() const { return &(*v_)[i_]; }
    const_iterator& operator++() { return ++i_, *this; }
    const_iterator operator++(int) { return {v_, i_++}; }
    const_iterator& operator--() { return --i_, *this; }
    const_iterator& operator+=(difference_type n) { return i_ += n, *this; }
    const_iterator operator+(difference_type n) const { return {v_, i_ + n}; }
    const_iterator operator-(difference_type n) const { return {v_, i_ - n}; }
    difference_type operator-(const const_iterator& o) const {
      return static_cast<difference_type>(i_) - static_cast<difference_type>(o.i_);
    }
    reference operator[](difference_type n) const { return (*v_)[i_ + n]; }
    bool operator==(const const_iterator& o) const { return i_ == o.i_; }
    bool operator!=(const const_iterator& o) const { return i_ != o.i_; }
    bool operator<(const const_iterator& o) const { return i_ < o.i_; }

   private:
    const CowVector* v_;
    size_t i_;
  };

  CowVector() = default;
  explicit CowVector(std::vector<T> items) {
    size_ = items.size();
    for (size_t at = 0; at < size_; at += kChunk) {
      const size_t end = std::min(size_, at + kChunk);
      chunks_.push_back(std::make_shared<const Chunk>(std::make_move_iterator(items.begin() + at),
                                                      std::make_move_iterator(items.begin() + end)));
    }
  }

  size_t size() const { return size_; }
  bool empty() const { return size_ == 0; }
  const T& operator[](size_t i) const { return (*chunks_[i / kChunk])[i % kChunk]; }
  const T& at(size_t i) const {
    if (i >= size_) throw std::out_of_range("CowVector::at");
    return (*this)[i];
  }
  const T& back() const { return (*this)[size_ - 1]; }
  const_iterator begin() const { return {this, 0}; }
  const_iterator end() const { return {this, size_}; }

  // A writable element. Its chunk is copied first (copies of this vector keep the old one), so the
  // reference is good until the next call that changes this vector.
  T& edit(size_t i) {
    if (i >= size_) throw std::out_of_range("CowVector::edit");
    auto own = std::make_shared<Chunk>(*chunks_[i / kChunk]);
    T& out = (*own)[i % kChunk];
    chunks_[i / kChunk] = std::move(own);
    return out;
  }
  void set(size_t i, T value) { edit(i) = std::move(value); }

  void push_back(T value) {
    if (size_ % kChunk == 0) {
      auto fresh = std::make_shared<Chunk>();
      fresh->reserve(kChunk);
      chunks_.push_back(std::move(fresh));
    } else {
      chunks_.back() = std::make_shared<Chunk>(*chunks_.back());
    }
    std::const_pointer_cast<Chunk>(chunks_.back())->push_back(std::move(value));
    ++size_;
  }

  // Keeps the first `n` elements (n <= size()).
  void truncate(size_t n) {
    if (n >= size_) return;
    chunks_.resize((n + kChunk - 1) / kChunk);
    if (n % kChunk != 0) {
      auto last = std::make_shared<Chunk>(chunks_.back()->begin(), chunks_.back()->begin() + n % kChunk);
      chunks_.back() = std::move(last);
    }
    size_ = n;
  }

  std::vector<T> to_vector() const { return std::vector<T>(begin(), end()); }
  // True when `other` holds element i in the same storage (a copy not written to there since).
  bool shares_element(const CowVector& other, size_t i) const {
    return i < size_ && i < other.size_ && chunks_[i / kChunk] == other.chunks_[i / kChunk];
  }

 private:
  // Written only through a pointer made in this object and not yet handed to a copy (edit, push_back,
  // truncate make a fresh chunk before writing).
  std::vector<std::shared_ptr<const Chunk>> chunks_;
  size_t size_ = 0;
};

}  // namespace ipd
