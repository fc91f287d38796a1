#pragma once
// The colours every figure shares, so that "valid" looks the same in all of them (colour-blind
// safe pairs from ColorBrewer).

namespace scanloc::figure_style {

inline constexpr const char* kMapPoint = "#969696";
inline constexpr const char* kLineMap = "#3a3a3a";
inline constexpr const char* kScan = "#e66101";
inline constexpr const char* kValid = "#1a9850";
inline constexpr const char* kInvalid = "#d73027";
inline constexpr const char* kRefined = "#2166ac";
inline constexpr const char* kTrajectory = "#2166ac";
inline constexpr const char* kClosure = "#f1a340";  // an accepted loop closure
inline constexpr const char* kBefore = "#4d4d4d";   // histogram before refinement (background)
inline constexpr const char* kAfter = "#92c5de";    // histogram after refinement (foreground)
inline constexpr const char* kAxis = "#555";
inline constexpr const char* kGrid = "#e4e4e4";
inline constexpr const char* kFrame = "#999";
inline constexpr const char* kMessage = "#888";

}  // namespace scanloc::figure_style
