// An array whose copies share one allocation until one of them is changed (copy on write): a relief texture's texels,
// displacements and discontinuity marks. A scene that places one relief file many times (each placement with its own
// geometry) then keeps one copy of the file's texels, not one per placement (docs/SCENES.md, "Memory").
//
// Reading is a std::vector's (size, data, operator[], iteration, comparison). Changing goes through edit(), which
// first makes the array this object's own when another copy shares it, and returns the std::vector to change. The
// reference edit() returns belongs to this object alone until the object is copied: do not keep it across a copy
// (the copy would see the later changes).
#pragma once

#include <cstddef>
#include <memory>
#include <utility>
#include <vector>

namespace rtm {

template <class T>
class SharedArray {
public:
    SharedArray() = default;
    SharedArray(std::vector<T> v) : v_(std::make_shared<std::vector<T>>(std::move(v))) {}  // NOLINT: from a vector

    size_t size() const { return v_ ? v_->size() : 0; }
    bool empty() const { return size() == 0; }
    const T* data() const { return v_ ? v_->data() : nullptr; }
    const T& operator[](size_t i) const { return (*v_)[i]; }
    const T* begin() const { return data(); }
    const T* end() const { return data() + size(); }
    const std::vector<T>& vector() const { return v_ ? *v_ : empty_vector(); }

    // The array to change: this object's own (copied first if another object shares it).
    std::vector<T>& edit() {
        if (!v_)
            v_ = std::make_shared<std::vector<T>>();
        else if (v_.use_count() > 1)
            v_ = std::make_shared<std::vector<T>>(*v_);
        return *v_;
    }
    // Replaces the contents (shares nothing with the former array).
    SharedArray& operator=(std::vector<T> v) {
        v_ = std::make_shared<std::vector<T>>(std::move(v));
        return *this;
    }
    void clear() { v_.reset(); }

    // Whether this object and `o` read the same allocation (both empty counts as no).
    bool shares_storage_with(const SharedArray& o) const { return v_ && v_ == o.v_; }

    friend bool operator==(const SharedArray& a, const SharedArray& b) {
        return a.v_ == b.v_ || a.vector() == b.vector();
    }

private:
    std::shared_ptr<std::vector<T>> v_;  // null when empty and never edited

    static const std::vector<T>& empty_vector() {
        static const std::vector<T> e;
        return e;
    }
};

}  // namespace rtm
