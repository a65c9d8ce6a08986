#pragma once
/// @file
/// A method's error over an animation (`hairshadow animate`): e(t) = T_method - T_exact at the same
/// points in every frame. The mean |e| over points and frames says how wrong the shadow is; the
/// flicker, the mean |e(t+1) - e(t)| over points and consecutive frames, says how much that error
/// moves from frame to frame, which a viewer sees as crawling or popping layers (Yuksel & Keyser 2008,
/// section 1: layering artifacts "are especially significant in animated sequences"). The animation
/// loops, so the last frame's pair with the first counts too.

#include <hairshadow/core/error.hpp>

#include <cmath>
#include <cstddef>
#include <span>
#include <vector>

namespace hairshadow {

/// Sums a method's error frame by frame; keeps the first and the last frame's errors.
class temporal_error {
public:
    /// Adds a frame: the method's and the exact transmittance at the animation's points, in the same
    /// order every frame. Throws argument_error where the lengths differ from each other or from the
    /// first frame's.
    void add_frame(std::span<const float> method, std::span<const float> exact) {
        if (method.size() != exact.size()) throw argument_error("temporal error: the method's and the exact transmittance differ in length");
        if (frames_ > 0 && method.size() != last_.size()) throw argument_error("temporal error: a frame with another number of points");
        const bool first = frames_ == 0;
        if (first) first_.assign(method.size(), 0.0f), last_.assign(method.size(), 0.0f);
        for (std::size_t i = 0; i < method.size(); ++i) {
            const float e = method[i] - exact[i];
            error_sum_ += std::abs(e);
            if (first) first_[i] = e;
            else flicker_sum_ += std::abs(e - last_[i]);
            last_[i] = e;
        }
        ++frames_;
    }

    std::size_t frames() const noexcept { return frames_; }
    /// Mean |e| over every point of every frame; 0 before any frame.
    double mean_error() const noexcept { return samples() > 0 ? error_sum_ / samples() : 0.0; }
    /// Mean |e(t+1) - e(t)| over every point and each of the loop's frame pairs: frames - 1 in order,
    /// and the last frame to the first. 0 for fewer than two frames.
    double flicker() const noexcept {
        if (frames_ < 2 || last_.empty()) return 0.0;
        double sum = flicker_sum_;
        for (std::size_t i = 0; i < last_.size(); ++i) sum += std::abs(first_[i] - last_[i]);
        return sum / samples(); // frames pairs of points
    }

private:
    double samples() const noexcept { return double(last_.size()) * double(frames_); }

    std::vector<float> first_, last_; ///< e of the first frame and of the last one added
    double error_sum_ = 0.0, flicker_sum_ = 0.0;
    std::size_t frames_ = 0;
};

} // namespace hairshadow
