// hexlod_struct_layout() (hexlod.h): the byte layout of the ABI's structs as this build
// compiled them, so JS reads and writes them by field name and no offset is typed by hand
// outside the header. Sizes, offsets, types and array lengths all come from the compiler.
#include <cstddef>
#include <cstdio>
#include <type_traits>

#include "api/hexlod.h"

namespace {

// The scalar type of a member as the layout names it: f64, i32, u32 or ptr.
template <class T>
constexpr const char* typeName() {
    using Scalar = std::remove_extent_t<T>;
    if constexpr (std::is_pointer_v<Scalar>) return "ptr";
    else if constexpr (std::is_same_v<Scalar, double>) return "f64";
    else if constexpr (std::is_same_v<Scalar, int32_t>) return "i32";
    else {
        static_assert(std::is_same_v<Scalar, uint32_t>, "hexlod_struct_layout names f64, i32, u32 and pointers only");
        return "u32";
    }
}

char text[8192];
size_t length = 0;

void line(const char* format, const char* name, size_t a, const char* type = "", size_t count = 0) {
    const int written = std::snprintf(text + length, sizeof(text) - length, format, name, a, type, count);
    if (written > 0) length += size_t(written);
}

} // namespace

#define HEXLOD_STRUCT(S) line("%s %zu\n", #S, sizeof(S))
#define HEXLOD_FIELD(S, F)                                                                                                 \
    line(" %s %zu %s %zu\n", #F, offsetof(S, F), typeName<decltype(S::F)>(),                                              \
         std::is_array_v<decltype(S::F)> ? std::extent_v<decltype(S::F)> : 1)

extern "C" const char* hexlod_struct_layout(void) {
    if (length > 0) return text;
    HEXLOD_STRUCT(hexlod_scale);
    HEXLOD_FIELD(hexlod_scale, spacing_x_m);
    HEXLOD_FIELD(hexlod_scale, spacing_y_m);
    HEXLOD_FIELD(hexlod_scale, height_scale);
    HEXLOD_FIELD(hexlod_scale, height_offset_m);
    HEXLOD_FIELD(hexlod_scale, nodata_raw);
    HEXLOD_FIELD(hexlod_scale, has_nodata);
    HEXLOD_FIELD(hexlod_scale, reserved);
    HEXLOD_STRUCT(hexlod_field_info);
    HEXLOD_FIELD(hexlod_field_info, min_height_m);
    HEXLOD_FIELD(hexlod_field_info, max_height_m);
    HEXLOD_FIELD(hexlod_field_info, missing);
    HEXLOD_FIELD(hexlod_field_info, sample_bytes);
    HEXLOD_STRUCT(hexlod_tile_want);
    HEXLOD_FIELD(hexlod_tile_want, level);
    HEXLOD_FIELD(hexlod_tile_want, tx);
    HEXLOD_FIELD(hexlod_tile_want, ty);
    HEXLOD_FIELD(hexlod_tile_want, reserved);
    HEXLOD_FIELD(hexlod_tile_want, priority_px);
    HEXLOD_STRUCT(hexlod_mesh_settings);
    HEXLOD_FIELD(hexlod_mesh_settings, embedding);
    HEXLOD_STRUCT(hexlod_settings);
    HEXLOD_FIELD(hexlod_settings, tau_px);
    HEXLOD_FIELD(hexlod_settings, max_error_m);
    HEXLOD_FIELD(hexlod_settings, vertical_scale);
    HEXLOD_FIELD(hexlod_settings, budget_ms);
    HEXLOD_FIELD(hexlod_settings, max_operations);
    HEXLOD_FIELD(hexlod_settings, max_triangles);
    HEXLOD_FIELD(hexlod_settings, auto_tau);
    HEXLOD_FIELD(hexlod_settings, no_frustum_culling);
    HEXLOD_FIELD(hexlod_settings, no_backface_culling);
    HEXLOD_FIELD(hexlod_settings, morph_frames);
    HEXLOD_FIELD(hexlod_settings, layout);
    HEXLOD_FIELD(hexlod_settings, no_normals);
    HEXLOD_STRUCT(hexlod_camera);
    HEXLOD_FIELD(hexlod_camera, eye);
    HEXLOD_FIELD(hexlod_camera, target);
    HEXLOD_FIELD(hexlod_camera, up);
    HEXLOD_FIELD(hexlod_camera, tan_half_fov_y);
    HEXLOD_FIELD(hexlod_camera, aspect);
    HEXLOD_FIELD(hexlod_camera, viewport_height_px);
    HEXLOD_FIELD(hexlod_camera, near_m);
    HEXLOD_FIELD(hexlod_camera, far_m);
    HEXLOD_STRUCT(hexlod_frame);
    HEXLOD_FIELD(hexlod_frame, update_ms);
    HEXLOD_FIELD(hexlod_frame, tau_px);
    HEXLOD_FIELD(hexlod_frame, frame);
    HEXLOD_FIELD(hexlod_frame, memory_bytes);
    HEXLOD_FIELD(hexlod_frame, triangles);
    HEXLOD_FIELD(hexlod_frame, achieved_error_px);
    HEXLOD_FIELD(hexlod_frame, tile_bytes);
    HEXLOD_FIELD(hexlod_frame, version);
    HEXLOD_FIELD(hexlod_frame, converged);
    HEXLOD_FIELD(hexlod_frame, operations);
    HEXLOD_FIELD(hexlod_frame, splits);
    HEXLOD_FIELD(hexlod_frame, merges);
    HEXLOD_FIELD(hexlod_frame, cells_tested);
    HEXLOD_FIELD(hexlod_frame, pending_merges);
    HEXLOD_FIELD(hexlod_frame, cells);
    HEXLOD_FIELD(hexlod_frame, vertices);
    HEXLOD_FIELD(hexlod_frame, max_level);
    HEXLOD_FIELD(hexlod_frame, full_hexagons);
    HEXLOD_FIELD(hexlod_frame, semi_hexagons);
    HEXLOD_FIELD(hexlod_frame, boundary_semi_hexagons);
    HEXLOD_FIELD(hexlod_frame, hash_low);
    HEXLOD_FIELD(hexlod_frame, hash_high);
    HEXLOD_FIELD(hexlod_frame, vertex_count);
    HEXLOD_FIELD(hexlod_frame, index_count);
    HEXLOD_FIELD(hexlod_frame, dirty_vertex_pairs);
    HEXLOD_FIELD(hexlod_frame, dirty_index_pairs);
    HEXLOD_FIELD(hexlod_frame, refined);
    HEXLOD_FIELD(hexlod_frame, tiles_evicted);
    HEXLOD_FIELD(hexlod_frame, vertices_ptr);
    HEXLOD_FIELD(hexlod_frame, indices_ptr);
    HEXLOD_FIELD(hexlod_frame, dirty_vertices_ptr);
    HEXLOD_FIELD(hexlod_frame, dirty_indices_ptr);
    HEXLOD_FIELD(hexlod_frame, normals_ptr);
    HEXLOD_STRUCT(hexlod_level_view);
    HEXLOD_FIELD(hexlod_level_view, indices);
    HEXLOD_FIELD(hexlod_level_view, level_offsets);
    HEXLOD_FIELD(hexlod_level_view, outline);
    HEXLOD_FIELD(hexlod_level_view, index_count);
    HEXLOD_FIELD(hexlod_level_view, level_offset_count);
    HEXLOD_FIELD(hexlod_level_view, outline_count);
    return text;
}
