/* shadowkit's C API: the core's shadow set-up (shadow_setup.h, engine_camera.h,
 * output_conventions.h; local_lights.h for spot and point lights) over plain structs of doubles and ints, for engines
 * in C, Rust, C#, Zig or anything with a C FFI. No allocation crosses the boundary: the caller owns every struct, and a
 * set-up holds at most SHADOWKIT_MAX_VIEWS maps.
 *
 * Matrices are 16 doubles, column-major (element [column * 4 + row]), acting on column
 * vectors: the layout of glm, GLSL, and of HLSL with column_major packing.
 *
 *     shadowkit_inputs in;
 *     shadowkit_default_inputs(&in);            // technique TSM, 2048², the recommended bias
 *     in.camera.use_matrices = 1;               // the engine's own camera
 *     memcpy(in.camera.view_from_world, view, sizeof view);
 *     memcpy(in.camera.clip_from_view, proj, sizeof proj);
 *     in.camera.shadow_distance = 150.0;
 *     ... light_direction, scene_min, scene_max, output conventions ...
 *     shadowkit_setup out;
 *     char error[256];
 *     if (shadowkit_compute_setup(&in, &out, error, sizeof error) != 0) puts(error);
 */
#ifndef SHADOWKIT_C_H
#define SHADOWKIT_C_H

#include <stddef.h>

#include "shadowkit/core/export.h"

#ifdef __cplusplus
extern "C" {
#endif

/** The most maps a set-up holds (cascades, 1 .. 8). */
#define SHADOWKIT_MAX_VIEWS 8

/** The techniques of the seed papers (shadowkit_inputs::technique). */
typedef enum shadowkit_technique {
    SHADOWKIT_TECHNIQUE_STANDARD = 0, /**< the whole scene box, orthographic (Williams 1978) */
    SHADOWKIT_TECHNIQUE_FOCUSED = 1,  /**< uniform, fitted to the focus body */
    SHADOWKIT_TECHNIQUE_LISPSM = 2,   /**< light space perspective (Wimmer et al. 2004) */
    SHADOWKIT_TECHNIQUE_PSM = 3,      /**< post-perspective space (Stamminger & Drettakis 2002) */
    SHADOWKIT_TECHNIQUE_TSM = 4,      /**< trapezoidal (Martin & Tan 2004), linear depth */
    SHADOWKIT_TECHNIQUE_CSM = 5       /**< cascades (Dimitrov 2007), optionally LiSPSM per split */
} shadowkit_technique;

/** The clip-space depth range of a projection. */
typedef enum shadowkit_clip_depth {
    SHADOWKIT_CLIP_DEPTH_ZERO_TO_ONE = 0,     /**< Vulkan, Direct3D, Metal, GL with glClipControl */
    SHADOWKIT_CLIP_DEPTH_MINUS_ONE_TO_ONE = 1 /**< OpenGL's default */
} shadowkit_clip_depth;

/** Where texture coordinate v = 0 lies in the map. */
typedef enum shadowkit_texture_origin {
    SHADOWKIT_TEXTURE_ORIGIN_BOTTOM_LEFT = 0, /**< OpenGL, Vulkan */
    SHADOWKIT_TEXTURE_ORIGIN_TOP_LEFT = 1     /**< Direct3D, Metal */
} shadowkit_texture_origin;

/** What a map stores as depth. */
typedef enum shadowkit_depth_layout {
    SHADOWKIT_DEPTH_HYPERBOLIC = 0, /**< the rasteriser's depth: reference depth = texture z / w */
    SHADOWKIT_DEPTH_LINEAR = 1      /**< written per fragment: dot(linear_depth_from_world, (p, 1)) */
} shadowkit_depth_layout;

/** The engine's camera: its matrices, or eye, direction and a symmetric frustum. */
typedef struct shadowkit_camera {
    /** 1: the engine's matrices below; 0: eye, direction, up, fov, aspect, near, far. */
    int use_matrices;
    double view_from_world[16]; /**< rigid */
    double clip_from_view[16];  /**< perspective or orthographic; reversed-Z and infinite far recognised */
    int clip_depth;             /**< shadowkit_clip_depth of clip_from_view */
    int left_handed;            /**< orthographic projections only: 1 if the view looks down +Z */
    /** Shadows end at this view depth (metres), whatever the far plane; <= 0: at the far plane.
       Required with an infinite far plane. */
    double shadow_distance;
    double eye[3];        /**< without matrices: the eye, world space */
    double direction[3];  /**< without matrices: the view direction, any length > 0 */
    double up[3];         /**< without matrices: up, not parallel to the direction */
    double fov_y_degrees; /**< without matrices: vertical field of view */
    double aspect;        /**< without matrices: width / height */
    double z_near;        /**< without matrices: near plane distance, > 0 */
    double z_far;         /**< without matrices: far plane distance, > z_near */
} shadowkit_camera;

/** Everything a set-up is computed from (start from shadowkit_default_inputs). */
typedef struct shadowkit_inputs {
    shadowkit_camera camera;   /**< the view the shadows are for */
    double light_direction[3]; /**< the direction sunlight travels (sun -> scene), any length > 0 */
    double scene_min[3];       /**< the scene box's lower corner: every caster and receiver lies inside */
    double scene_max[3];       /**< its upper corner */
    int technique;             /**< shadowkit_technique */
    int map_size;              /**< texels per side of each map */
    int cascade_count;         /**< csm: splits, 1 .. SHADOWKIT_MAX_VIEWS */
    double cascade_lambda;     /**< csm: 0 uniform .. 1 logarithmic splits */
    int cascade_lispsm;        /**< csm: 1 warps each split with LiSPSM */
    double cascade_blend_band; /**< csm: [0, 0.5] of the previous split, for blending */
    /** Output conventions of the matrices in shadowkit_view. */
    int clip_depth;     /**< shadowkit_clip_depth */
    int reversed_z;     /**< 1: the light's near side stored as 1 */
    int texture_origin; /**< shadowkit_texture_origin */
    /** The sun's angular diameter in degrees, [0, 20] (the real sun 0.53; 0 a point): soft
       shadows' light size, returned as shadowkit_setup's light_tan_half_angle. */
    double sun_angle_degrees;
} shadowkit_inputs;

/** One shadow map of a set-up, in the requested output conventions. */
typedef struct shadowkit_view {
    double clip_from_world[16];        /**< draw the map with this */
    double texture_from_world[16];     /**< (u, v, d, 1) * w: look the map up with this */
    double linear_depth_from_world[4]; /**< linear layout: the depth to write and compare, dot(this, (p, 1)) */
    double culling_planes[6][4];       /**< (nx, ny, nz, d): a point p is outside when n.p + d > 0 */
    int culling_plane_count;           /**< planes in use in culling_planes */
    double split_near;                 /**< cascades: the nearest view depth this map serves; else 0 */
    double split_far;                  /**< cascades: the farthest; else 0 */
    /** Camera-relative rendering: the same for p - eye_relative_origin (shadowkit_setup). */
    double clip_from_eye_relative[16];        /**< clip_from_world for p - eye_relative_origin */
    double texture_from_eye_relative[16];     /**< texture_from_world for p - eye_relative_origin */
    double linear_depth_from_eye_relative[4]; /**< linear_depth_from_world for p - eye_relative_origin */
} shadowkit_view;

/** The recommended bias of a set-up (core::recommendedBias). */
typedef struct shadowkit_bias {
    double slope;    /**< glPolygonOffset factor (per fragment for linear depth) */
    double constant; /**< 2^-24 of the depth range each: add constant·2^-24·w to clip z (not glPolygonOffset units) */
    double normal_offset;           /**< texels of world size (shadowkit_texel_size) along the normal */
    int receiver_plane;             /**< 1: receiver-plane depth bias in the lookup */
    double normal_offset_footprint; /**< × the texel's footprint across the light on the normal (SkShadowOptions) */
    int offset_guard; /**< 1: a receiver behind another caster keeps its shadow under the offsets (SkShadowOptions) */
} shadowkit_bias;

/** The result: one view per map, the depth layout, the bias. */
typedef struct shadowkit_setup {
    int technique;    /**< shadowkit_technique actually used */
    int map_size;     /**< texels per side of every map */
    int depth_layout; /**< shadowkit_depth_layout */
    int depth_clamp;  /**< 1: draw the map with depth clamping (GL_DEPTH_CLAMP, depthClampEnable) */
    int view_count;   /**< maps in use in views */
    shadowkit_view views[SHADOWKIT_MAX_VIEWS]; /**< the maps, nearest split first */
    shadowkit_bias bias;                       /**< the recommended bias for this technique and layout */
    double eye_relative_origin[3];             /**< the camera's eye: what the views' *_eye_relative take p minus */
    int fallback_count; /**< degenerate cases met (view along the light, a view missing the scene) */
    /** tan of the sun's angular *radius* (half of sun_angle_degrees): the GLSL's
       SkShadowOptions.lightTanHalfAngle for SK_FILTER_PCSS, 0.004625 for the real sun. */
    double light_tan_half_angle;
} shadowkit_setup;

/** The defaults of the C++ API: technique TSM, 2048², cascades 4 / 0.9, a camera 1.8 m up
   looking north, OpenGL-with-glClipControl conventions. */
SHADOWKIT_CORE_EXPORT void shadowkit_default_inputs(shadowkit_inputs* inputs);

/** 0 on success. Otherwise non-zero, `out` untouched, and a one-line message naming the input
   in `error` (truncated to error_size, always terminated when error_size > 0). */
SHADOWKIT_CORE_EXPORT int shadowkit_compute_setup(const shadowkit_inputs* inputs, shadowkit_setup* out, char* error,
                                                  size_t error_size);

/** World size (metres) of one texel of `view` at `point` on a plane facing the light;
   +inf where the map's projection degenerates. */
SHADOWKIT_CORE_EXPORT double shadowkit_texel_size(const shadowkit_view* view, int map_size,
                                                  const double light_direction[3], const double point[3]);

/** PCSS's light size in `view`'s own texels at `point`: the radius, in texels, of the cone of a sun
   sun_angle_degrees across one metre towards it (times a blocker's distance in metres: the
   penumbra's half-width). It changes over warped maps and between cascades, so an engine's own
   PCSS takes it per receiver or per map; 0 for a point sun or where the projection degenerates. */
SHADOWKIT_CORE_EXPORT double shadowkit_penumbra_texels_per_metre(const shadowkit_view* view, int map_size,
                                                                 const double light_direction[3],
                                                                 double sun_angle_degrees, const double point[3]);

/** Spot and point lights (shadowkit_local_inputs::kind; core/local_lights.h, seed 003). */
typedef enum shadowkit_light_kind {
    SHADOWKIT_LIGHT_SPOT = 0,           /**< one perspective map over its cone */
    SHADOWKIT_LIGHT_POINT = 1,          /**< a cube of six 90° faces */
    SHADOWKIT_LIGHT_POINT_ONE_MAP = 2,  /**< a point light in one map, for engines without cube maps: the narrowest
                                             cone over what the camera sees in its range (computePointSingleMapSetup);
                                             refused, naming "position", where that spans more than 170° */
    SHADOWKIT_LIGHT_POINT_AIMED_MAP = 3 /**< a point light in one map wherever it stands: ONE_MAP's, or where that
                                             is refused (a lamp among or beside what the camera sees) a 170° cone
                                             aimed at the middle of it, holds_part_of_view set: receivers outside
                                             the cone get no shadow (computePointSingleOrAimedMapSetup) */
} shadowkit_light_kind;

/** A spot or point light and what its maps are fitted to (start from shadowkit_default_local_inputs). */
typedef struct shadowkit_local_inputs {
    shadowkit_camera camera; /**< the view the shadows are for: each map covers what it sees of the light */
    double scene_min[3];     /**< the scene box's lower corner: every caster and receiver lies inside */
    double scene_max[3];     /**< its upper corner */
    int map_size;            /**< texels per side of the spot map or of each cube face */
    int kind;                /**< shadowkit_light_kind */
    double position[3];      /**< the light, world space */
    double direction[3];     /**< spot: the cone's axis, any length > 0 */
    double cone_degrees;     /**< spot: the cone's full opening angle, (0, 170] */
    double range;            /**< metres: nothing farther is lit, > 0 */
    double radius;           /**< metres: the lamp's sphere (PCSS's penumbrae), [0, range); 0 a point */
    /** Output conventions of the matrices in shadowkit_view, and of stored_from_distance. */
    int clip_depth;     /**< shadowkit_clip_depth */
    int reversed_z;     /**< 1: the light's near side stored as 1 */
    int texture_origin; /**< shadowkit_texture_origin */
} shadowkit_local_inputs;

/** The local lights' lookup biases (core::LocalBias; SkLocalShadowOptions in
   shadowkit_local_shadows.glsl), in the map's texels at the receiver's distance and metres. */
typedef struct shadowkit_local_bias {
    double slope_texels;         /**< distance reduced by this × texel size × tan(angle to the light), tan ≤ 3.2 */
    double normal_offset_texels; /**< receiver moved along its normal by this × texel size where the light grazes it */
    double constant_metres;      /**< and its distance reduced by this */
} shadowkit_local_bias;

/** A local light's maps: a spot light's one view, or the cube faces of a point light that see
   something of the view (the others: clear them to the far value). Draw each view with its
   clip_from_world into its face's layer, writing per fragment
   distance(p, light_position) · stored_from_distance[0] + stored_from_distance[1]. */
typedef struct shadowkit_local_setup {
    int kind;                 /**< the maps' shadowkit_light_kind: SPOT for a point light in one map (drawn and
                                   looked up as a spot's: skSpotShadow) */
    int map_size;             /**< texels per side of the spot map or of each cube face */
    int depth_clamp;          /**< 1: draw with depth clamping (GL_DEPTH_CLAMP, depthClampEnable) */
    int view_count;           /**< views in use: 0 when the light reaches nothing the camera sees */
    shadowkit_view views[6];  /**< clip_from_world, texture_from_world (a spot's (u, v) = xy / w), culling planes */
    int faces[6];             /**< point lights: each view's cube face, 0–5 in OpenGL's order; spot lights 0 */
    double light_position[3]; /**< SkLocalLight.wsPosition */
    double stored_from_distance[2]; /**< SkLocalLight.storedFromDistance: (1 / range, 0), reversed (−1 / range, 1) */
    double texel_per_metre;         /**< SkLocalLight.texelPerMetre: a texel's world size per metre of distance */
    double radius;                  /**< SkLocalLight.radius: the lamp's, for PCSS */
    shadowkit_local_bias bias;      /**< the recommended biases */
    int holds_part_of_view; /**< 1: SHADOWKIT_LIGHT_POINT_AIMED_MAP's aimed cone, which holds only part of what the
                                 camera sees within range (ShadowSetup::holdsPartOfView); skSpotShadow reads
                                 the receivers it leaves out lit (skSpotMapHolds) */
} shadowkit_local_setup;

/** A spot light 3 m up looking down, 40°, 30 m; the default camera and a 1024² map; OpenGL-with-
   glClipControl conventions. */
SHADOWKIT_CORE_EXPORT void shadowkit_default_local_inputs(shadowkit_local_inputs* inputs);

/** 0 on success. Otherwise non-zero, `out` untouched, and a one-line message naming the input in
   `error`, as shadowkit_compute_setup. */
SHADOWKIT_CORE_EXPORT int shadowkit_compute_local_setup(const shadowkit_local_inputs* inputs,
                                                        shadowkit_local_setup* out, char* error, size_t error_size);

/** "major.minor.patch" of the library linked. */
SHADOWKIT_CORE_EXPORT const char* shadowkit_version_string(void);

#ifdef __cplusplus
}
#endif

#endif /* SHADOWKIT_C_H */
