// What the viewer's composite pass shows (view::ViewMode): defined once, here, for the C++
// viewer and view_composite.frag.
#ifndef SUBDFIT_VIEW_MODES_H
#define SUBDFIT_VIEW_MODES_H

#define SUBDFIT_VIEW_FIT 0
#define SUBDFIT_VIEW_TARGET 1
#define SUBDFIT_VIEW_DIFFERENCE 2
#define SUBDFIT_VIEW_FACE_ID 3
#define SUBDFIT_VIEW_UV 4
#define SUBDFIT_VIEW_DISPLACEMENT 5
#define SUBDFIT_VIEW_NORMAL_MAP 6
#define SUBDFIT_VIEW_BASE_COLOR 7
#define SUBDFIT_VIEW_METALLIC_ROUGHNESS 8
#define SUBDFIT_VIEW_MODE_COUNT 9

#endif
