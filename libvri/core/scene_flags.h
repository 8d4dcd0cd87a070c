#pragma once
// The command-line spellings of the scene options, every rendering tool's: what is rendered (a volume file
// and its raw layout, or an analytic field), its grid convention, the transfer function, the camera and the
// 8-bit preview. The tools declare their options with these (tools/common) and the experiment reader writes
// them into the steps' commands, so that renaming a flag is a compile error in both, not a step that fails
// when it runs. The render options' spellings are rows of render_option_table.h.
namespace vri::scene_flag {

inline constexpr const char* volume = "--volume";
inline constexpr const char* dims = "--dims";
inline constexpr const char* type = "--type";
inline constexpr const char* byteOrder = "--byte-order";
inline constexpr const char* headerBytes = "--header-bytes";
inline constexpr const char* spacing = "--spacing";
inline constexpr const char* storage = "--storage";
inline constexpr const char* range = "--range";
inline constexpr const char* bricks = "--bricks";
inline constexpr const char* brick = "--brick";
inline constexpr const char* field = "--field";
inline constexpr const char* fieldDims = "--field-dims";
inline constexpr const char* fieldAsGrid = "--field-as-grid";
inline constexpr const char* convention = "--convention";
inline constexpr const char* tf = "--tf";
inline constexpr const char* size = "--size";
inline constexpr const char* eye = "--eye";
inline constexpr const char* target = "--target";
inline constexpr const char* up = "--up";
inline constexpr const char* fov = "--fov";
inline constexpr const char* zoom = "--zoom";
inline constexpr const char* zoomCentre = "--zoom-centre";
inline constexpr const char* pngExposure = "--png-exposure";
inline constexpr const char* pngInvert = "--png-invert";
inline constexpr const char* background = "--background";

}  // namespace vri::scene_flag
