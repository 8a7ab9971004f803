/* The C API from C: default inputs, one set-up, a bad input named, a point light's cube, the version. */
#include "shadowkit/shadowkit_c.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

int main(void) {
    shadowkit_inputs in;
    shadowkit_setup out;
    shadowkit_local_inputs lamp;
    shadowkit_local_setup cube;
    char error[256];
    int i;
    shadowkit_default_inputs(&in);
    in.scene_min[0] = -100, in.scene_min[1] = 0, in.scene_min[2] = -100;
    in.scene_max[0] = 100, in.scene_max[1] = 20, in.scene_max[2] = 100;
    in.light_direction[0] = 0.3, in.light_direction[1] = -0.8, in.light_direction[2] = 0.2;
    in.technique = SHADOWKIT_TECHNIQUE_CSM;
    in.cascade_lispsm = 1;
    if (shadowkit_compute_setup(&in, &out, error, sizeof error) != 0) {
        fprintf(stderr, "c_api_smoke: %s\n", error);
        return 1;
    }
    if (out.view_count != in.cascade_count) return 2;
    for (i = 0; i < out.view_count; ++i)
        if (!isfinite(out.views[i].texture_from_world[0]) || !(out.views[i].split_far > out.views[i].split_near))
            return 3;

    in.map_size = 3; /* below the smallest map: refused, with the input named */
    if (shadowkit_compute_setup(&in, &out, error, sizeof error) == 0 || strstr(error, "map_size") == NULL) return 4;

    /* A point lamp in front of the camera: the faces that see the view, each with its cube face. */
    shadowkit_default_local_inputs(&lamp);
    lamp.camera = in.camera;
    memcpy(lamp.scene_min, in.scene_min, sizeof lamp.scene_min);
    memcpy(lamp.scene_max, in.scene_max, sizeof lamp.scene_max);
    lamp.kind = SHADOWKIT_LIGHT_POINT;
    lamp.position[0] = in.camera.eye[0] + 10.0 * in.camera.direction[0];
    lamp.position[1] = 3.0;
    lamp.position[2] = in.camera.eye[2] + 10.0 * in.camera.direction[2];
    if (shadowkit_compute_local_setup(&lamp, &cube, error, sizeof error) != 0) {
        fprintf(stderr, "c_api_smoke: %s\n", error);
        return 5;
    }
    if (cube.view_count < 1 || cube.view_count > 6 || !(cube.stored_from_distance[0] > 0.0)) return 6;
    for (i = 0; i < cube.view_count; ++i)
        if (cube.faces[i] < 0 || cube.faces[i] > 5) return 7;
    printf("shadowkit %s from C: %d cascades, refused map_size 3 with \"%s\", a point lamp in %d cube faces\n",
           shadowkit_version_string(), in.cascade_count, error, cube.view_count);
    return 0;
}
