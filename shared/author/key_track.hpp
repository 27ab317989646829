#pragma once
// Key poses + smooth interpolation: a track of timed keys interpolated by cubic Hermite segments
// with Catmull-Rom tangents (C1 through the keys). A key flagged `hold` has zero velocity, so the
// motion eases into and out of it: the right thing at a strike's full extension or at the stance.
// The first and last keys always hold. Works for float and vec3.
#include "author/easing.hpp"

#include <cassert>
#include <vector>

namespace foresight::author {

template <class T>
class KeyTrack {
 public:
  KeyTrack& key(float t_s, T value, bool hold = false) {
    assert(keys_.empty() || t_s > keys_.back().t_s);
    keys_.push_back({t_s, value, hold});
    return *this;
  }
  bool empty() const { return keys_.empty(); }

  T at(float t_s) const {
    assert(!keys_.empty());
    if (t_s <= keys_.front().t_s) return keys_.front().value;
    if (t_s >= keys_.back().t_s) return keys_.back().value;
    size_t i = 0;
    while (t_s > keys_[i + 1].t_s) ++i;
    const Key& a = keys_[i];
    const Key& b = keys_[i + 1];
    const float span = b.t_s - a.t_s;
    // Tangents scaled to the segment's length so unequal key spacing stays smooth.
    const T ma = tangent(i) * span;
    const T mb = tangent(i + 1) * span;
    return hermite(a.value, ma, b.value, mb, (t_s - a.t_s) / span);
  }

 private:
  struct Key {
    float t_s;
    T value;
    bool hold;
  };
  // Velocity at key i (value per second): zero at holds and ends, else the Catmull-Rom chord.
  T tangent(size_t i) const {
    if (i == 0 || i + 1 >= keys_.size() || keys_[i].hold) return keys_[i].value * 0.0f;
    return (keys_[i + 1].value - keys_[i - 1].value) / (keys_[i + 1].t_s - keys_[i - 1].t_s);
  }
  std::vector<Key> keys_;
};

}  // namespace foresight::author
