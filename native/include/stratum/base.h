/* Stratum C ABI, part 1 of 4 (stratum/stratum.h includes them all and states the rules):
 * status codes, errors, version, the model and render-setting listings. */
#ifndef STRATUM_BASE_H
#define STRATUM_BASE_H

#include <stddef.h>
#include <stdint.h>

#if defined(_WIN32)
#define STRATUM_API __declspec(dllexport)
#else
#define STRATUM_API __attribute__((visibility("default")))
#endif

#ifdef __cplusplus
extern "C" {
#endif

typedef enum StratumStatus {
    STRATUM_OK = 0,
    STRATUM_ERROR_INVALID_ARGUMENT = 1, /* a value was rejected; see stratum_last_error() */
    STRATUM_ERROR_INVALID_STATE = 2,    /* e.g. a setting changed while rendering */
    STRATUM_ERROR_OUT_OF_MEMORY = 3,
    STRATUM_ERROR_INTERNAL = 4, /* a library (Embree, OIIO) failed; message says which */
    STRATUM_ERROR_IO = 5        /* a file could not be read or written */
} StratumStatus;

/* Message of the last failed call made on the calling thread ("" if none). Valid until the
 * next Stratum call on this thread. */
STRATUM_API const char* stratum_last_error(void);
STRATUM_API const char* stratum_version(void);

/* ---- models (light types, closure models, shader node types) ------------------------------ */

typedef enum StratumModelKind {
    STRATUM_MODEL_LIGHT = 0,      /* StratumLightType */
    STRATUM_MODEL_CLOSURE = 1,    /* StratumMaterialModel */
    STRATUM_MODEL_SHADER_NODE = 2 /* StratumShaderNode::type (stratum/shader_nodes.h) */
} StratumModelKind;

/* Number of models of a kind, or -1 for an unknown kind. */
STRATUM_API int32_t stratum_model_count(int32_t kind);
/* Model `index` of a kind, in value order: its name (static) and its value. A light type's or a
 * closure model's name is its enumerator's, in lower case, without its prefix ("spot_v1" for
 * STRATUM_LIGHT_SPOT_V1); a shader node type's is docs/shader_nodes.md's ("vector_math"), and
 * the header has no enumerator for it. Hosts look values up by name here instead of mirroring
 * them. */
STRATUM_API StratumStatus stratum_model_entry(int32_t kind, int32_t index, const char** name, int32_t* value);

/* ---- render settings ---------------------------------------------------------------------- */

/* Every render setting, listed once: hosts build their menus, choices, help and tables from it.
 * INT settings are set with stratum_renderer_set_int, FLOAT with _set_float, CHOICE (one name of
 * its choices) and LIST (comma-separated names of its choices, "" = none) with _set_string. */
typedef enum StratumSettingKind {
    STRATUM_SETTING_INT = 0,
    STRATUM_SETTING_FLOAT = 1,
    STRATUM_SETTING_CHOICE = 2,
    STRATUM_SETTING_LIST = 3
} StratumSettingKind;

typedef struct StratumSettingInfo {
    const char* name;        /* as set: "light_sampling" */
    const char* label;       /* for a menu: "Light Sampling" */
    const char* description; /* one sentence */
    int32_t kind;            /* StratumSettingKind */
    double minimum;          /* INT, FLOAT: the accepted range (FLOAT: maximum may be +inf) */
    double maximum;
    int32_t open_minimum;      /* FLOAT: 1 when the minimum itself is excluded */
    const char* unit;          /* "pixels", "scene units" or "" */
    const char* default_value; /* the renderer's default as text: "16", "1.5", "mis", "" */
    int32_t choice_count;      /* CHOICE, LIST: number of choices (stratum_setting_choice) */
} StratumSettingInfo;

STRATUM_API int32_t stratum_setting_count(void);
/* The setting at `index` (0 <= index < stratum_setting_count()); the strings are static. */
STRATUM_API StratumStatus stratum_setting_info(int32_t index, StratumSettingInfo* out);
/* Choice `choice` of setting `setting`, in menu order (a host may store the position: the order
 * only grows at the end): stable name, label and description (static strings). */
STRATUM_API StratumStatus stratum_setting_choice(int32_t setting, int32_t choice, const char** name,
                                                 const char** label, const char** description);

#ifdef __cplusplus
}
#endif

#endif
