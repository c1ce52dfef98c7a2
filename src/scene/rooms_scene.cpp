#include "scene/rooms_scene.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "core/error.h"
#include "scene/box_layout.h"
#include "scene/light_generator.h"
#include "scene/procedural_meshes.h"
#include "shading.h"

namespace punctual {
namespace rooms_scene {
namespace {

// ---- sizes -----------------------------------------------------------------------------------

constexpr float kWallThickness = 0.2f;
constexpr float kDoorWidth = 1.2f;
constexpr float kDoorHeight = 2.2f;
constexpr float kCellSide = 2.0f;  // each room is a 4 x 4 grid of cells; one piece of furniture a cell
constexpr uint32_t kCellsPerSide = 4;
constexpr uint32_t kFoliageCards = 6;  // three crossed pairs

// The column's profile (radius, height): a plinth, the shaft, a capital. Fixed: 6 points.
constexpr std::array<glm::vec2, 6> kColumnProfile = {{{0.34f, 0.0f}, {0.34f, 0.12f}, {0.26f, 0.22f},
                                                      {0.26f, 2.78f}, {0.34f, 2.88f}, {0.34f, kWallHeight}}};

// Triangles per room that do not depend on the tessellation: the floor and the crates (boxes, 12
// each), two walls with a door (three boxes each), the table (top and four legs), the planter
// and its cards (2 each).
uint64_t fixedRoomTriangles(uint32_t crates) { return 12 + 2 * 36 + 12ull * crates + 60 + 12 + 2 * kFoliageCards; }

// Rooms along the grid's east and south edges close it with a plain wall (one box each).
uint32_t outerWalls(uint32_t rooms, uint32_t columns) {
    uint32_t walls = 0;
    for (uint32_t i = 0; i < rooms; ++i) {
        const uint32_t column = i % columns;
        if (column + 1 == columns || i + 1 == rooms) ++walls;  // nothing east
        if (i + columns >= rooms) ++walls;                     // nothing south
    }
    return walls;
}

}  // namespace

Layout layoutFor(uint64_t target) {
    if (target < kMinTriangles || target > kMaxTriangles) {
        throw Error("--scene-triangles", "expected " + std::to_string(kMinTriangles) + " to " +
                                             std::to_string(kMaxTriangles) + " triangles, got " + std::to_string(target));
    }
    Layout layout;
    // n = target / 10^4 rooms' worth; rooms n^0.875 = n / n^(1/8) (three square roots, exact in
    // IEEE arithmetic, unlike pow), so each room's share, n^(1/8) x 10^4 triangles, grows slowly:
    // the objects grow almost as fast as the triangles and the tessellation a little.
    const double n = double(target) / 1e4;
    layout.rooms = std::max(1u, uint32_t(std::lround(n / std::sqrt(std::sqrt(std::sqrt(n))))));
    layout.columns = uint32_t(std::ceil(std::sqrt(double(layout.rooms))));
    layout.rows = (layout.rooms + layout.columns - 1) / layout.columns;
    layout.cratesPerRoom = 2 + 2 * uint32_t(target >= 100'000) + 2 * uint32_t(target >= 1'000'000) +
                           2 * uint32_t(target >= 10'000'000);
    const uint64_t fixed = layout.rooms * fixedRoomTriangles(layout.cratesPerRoom) +
                           12ull * outerWalls(layout.rooms, layout.columns);
    // The round things take the rest: a column (fixed profile) and two lathes of `rings` points
    // (vase and barrel) per room, all with `segments` steps around. Segments about the square
    // root of a lathe's share keep its quads near square; the rings then take up what is left:
    //   rest = rooms x (column + 2 x (2 s (rings - 1) + 2 (s - 2)))
    //   => rings - 1 = (rest / rooms - column - 4 (s - 2)) / (4 s), rounded to the nearest.
    const double perRoom = double(target - std::min(target, fixed)) / double(layout.rooms);
    layout.segments = std::clamp(uint32_t(std::lround(std::sqrt(std::max(perRoom, 0.0) / 2.0))), 12u, 512u);
    const uint32_t s = layout.segments;
    const double column = double(latheTriangles(uint32_t(kColumnProfile.size()), s));
    const double ringsLessOne = (perRoom - column - 4.0 * (s - 2)) / (4.0 * s);
    layout.rings = uint32_t(std::max(2l, std::lround(ringsLessOne) + 1));
    layout.triangles = fixed + layout.rooms * (latheTriangles(uint32_t(kColumnProfile.size()), s) +
                                               2 * latheTriangles(layout.rings, s));
    return layout;
}

namespace {

// ---- materials -------------------------------------------------------------------------------

enum MaterialId : uint32_t {
    kOakFloor, kTileFloor, kPlaster, kStone, kCrateWood, kDarkWood, kGlaze, kSteel, kTerracotta, kFoliage
};

void addMaterials(Scene& scene) {
    // Order matches MaterialId. Albedos below ~0.8, as real materials.
    scene.materials = {
        plainMaterial("oak floor", {0.42f, 0.30f, 0.19f}, 0.0f, 0.7f),
        plainMaterial("tile floor", {0.55f, 0.55f, 0.52f}, 0.0f, 0.4f),
        plainMaterial("plaster", {0.70f, 0.68f, 0.62f}, 0.0f, 0.9f),
        plainMaterial("stone", {0.60f, 0.58f, 0.55f}, 0.0f, 0.75f),
        plainMaterial("crate wood", {0.50f, 0.36f, 0.20f}, 0.0f, 0.85f),
        plainMaterial("dark wood", {0.25f, 0.15f, 0.09f}, 0.0f, 0.5f),
        plainMaterial("blue glaze", {0.12f, 0.22f, 0.55f}, 0.0f, 0.2f),
        plainMaterial("steel", {0.60f, 0.61f, 0.63f}, 1.0f, 0.4f),
        plainMaterial("terracotta", {0.60f, 0.30f, 0.18f}, 0.0f, 0.9f),
        plainMaterial("foliage", {1.0f, 1.0f, 1.0f}, 0.0f, 0.8f),
    };
    // The foliage: leaves on cards, cut out by the texture's alpha (MASK), seen from both sides.
    Material& foliage = scene.materials[kFoliage];
    foliage.baseColorTexture.image = 0;
    foliage.baseColorTexture.sampler.wrapU = TextureWrap::ClampToEdge;
    foliage.baseColorTexture.sampler.wrapV = TextureWrap::ClampToEdge;
    foliage.alphaMode = AlphaMode::Mask;
    foliage.alphaCutoff = 0.5f;
    foliage.doubleSided = true;
    scene.textures.push_back(leafTexture(128, 0x6C6561766573ull));  // "leaves"
}

// ---- geometry --------------------------------------------------------------------------------

// A model matrix turning local +X to the world (x, z) direction `facing` about the vertical axis
// through `position`, then moving there (as addBoxes places its boxes: no angle, no sin/cos).
glm::mat4 placed(const glm::vec3& position, glm::vec2 facing) {
    const glm::vec2 x = glm::normalize(facing);
    return glm::mat4(glm::vec4(x.x, 0.0f, x.y, 0.0f), glm::vec4(0.0f, 1.0f, 0.0f, 0.0f),
                     glm::vec4(-x.y, 0.0f, x.x, 0.0f), glm::vec4(position, 1.0f));
}

void addObject(Scene& scene, const char* name, const MeshBuilder& mesh, uint32_t material,
               const glm::mat4& model = glm::mat4(1.0f)) {
    Object object;
    object.name = name;
    object.mesh = mesh.appendTo(scene, name, material);
    object.model = model;
    scene.objects.push_back(std::move(object));
}

// A wall `length` long from `start` along +x (alongX) or +z, with a door opening centred
// `doorAt` metres from the start: the two pieces either side and the lintel above.
MeshBuilder wallWithDoor(const glm::vec3& start, float length, bool alongX, float doorAt) {
    auto box = [&](float from, float to, float bottom, float top) {
        return alongX ? std::pair{start + glm::vec3(from, bottom, 0.0f), start + glm::vec3(to, top, kWallThickness)}
                      : std::pair{start + glm::vec3(0.0f, bottom, from), start + glm::vec3(kWallThickness, top, to)};
    };
    MeshBuilder wall;
    const float doorFrom = doorAt - 0.5f * kDoorWidth;
    const float doorTo = doorAt + 0.5f * kDoorWidth;
    for (const auto& [min, max] : {box(0.0f, doorFrom, 0.0f, kWallHeight), box(doorTo, length, 0.0f, kWallHeight),
                                   box(doorFrom, doorTo, kDoorHeight, kWallHeight)}) {
        wall.addBox(min, max);
    }
    return wall;
}

// A table, 1.4 x 0.9 m, 0.78 m high, centred on the local origin: top and four legs.
MeshBuilder table() {
    MeshBuilder mesh;
    mesh.addBox({-0.7f, 0.72f, -0.45f}, {0.7f, 0.78f, 0.45f});
    for (const float x : {-0.62f, 0.56f}) {
        for (const float z : {-0.39f, 0.33f}) mesh.addBox({x, 0.0f, z}, {x + 0.06f, 0.72f, z + 0.06f});
    }
    return mesh;
}

// The vase's and the barrel's profiles, `rings` points each: a vase bellying out below and
// narrowing to a neck, a barrel bulging at the middle. Polynomials in t = 0..1 up the profile.
std::vector<glm::vec2> vaseProfile(uint32_t rings) {
    std::vector<glm::vec2> profile;
    for (uint32_t j = 0; j < rings; ++j) {
        const float t = float(j) / float(rings - 1);
        const float belly = 4.0f * t * (1.0f - t);
        profile.emplace_back(0.07f + 0.09f * belly * (1.3f - t) + 0.03f * t * t * t, 0.45f * t);
    }
    return profile;
}
std::vector<glm::vec2> barrelProfile(uint32_t rings) {
    std::vector<glm::vec2> profile;
    for (uint32_t j = 0; j < rings; ++j) {
        const float t = float(j) / float(rings - 1);
        profile.emplace_back(0.28f + 0.06f * 4.0f * t * (1.0f - t), 0.9f * t);
    }
    return profile;
}

// Three crossed pairs of 0.9 x 1.1 m cards standing on a planter top at height `base`, turned
// 0, 60 and 120 degrees (unitCircle), all double-sided.
MeshBuilder foliageCards(float base) {
    MeshBuilder mesh;
    for (uint32_t i = 0; i < kFoliageCards; ++i) {
        const glm::vec2 d = unitCircle(i, 2 * kFoliageCards);  // 30 degree steps over half a turn
        mesh.addCard({0.0f, base + 0.55f, 0.0f}, glm::vec3(d.x, 0.0f, d.y), {0.0f, 1.0f, 0.0f}, 0.45f, 0.55f);
    }
    return mesh;
}

// A random whole number in [0, count).
uint32_t randomIndex(PortableRandom& random, uint32_t count) {
    return std::min(count - 1, uint32_t(random.uniform() * float(count)));
}

void addRoom(Scene& scene, const Layout& layout, uint32_t room, PortableRandom& random) {
    const uint32_t column = room % layout.columns;
    const uint32_t row = room / layout.columns;
    const glm::vec3 origin(float(column) * kRoomSide, 0.0f, float(row) * kRoomSide);  // the -x -z corner
    MeshBuilder floorSlab;
    floorSlab.addBox(origin + glm::vec3(0.0f, -0.2f, 0.0f), origin + glm::vec3(kRoomSide, 0.0f, kRoomSide));
    addObject(scene, "floor", floorSlab, (column + row) % 2 == 0 ? kOakFloor : kTileFloor);
    // The west and north walls, each with a door 1.6 to 6.4 m along it; the next room's walls
    // are this room's east and south ones.
    addObject(scene, "west wall", wallWithDoor(origin, kRoomSide, false, random.uniform(1.6f, 6.4f)), kPlaster);
    addObject(scene, "north wall",
              wallWithDoor(origin + glm::vec3(kWallThickness, 0.0f, 0.0f), kRoomSide - kWallThickness, true,
                           random.uniform(1.6f, 6.4f)),
              kPlaster);
    const bool nothingEast = column + 1 == layout.columns || room + 1 == layout.rooms;
    const bool nothingSouth = room + layout.columns >= layout.rooms;
    if (nothingEast) {
        MeshBuilder wall;
        wall.addBox(origin + glm::vec3(kRoomSide, 0.0f, 0.0f),
                    origin + glm::vec3(kRoomSide + kWallThickness, kWallHeight, kRoomSide));
        addObject(scene, "east wall", wall, kPlaster);
    }
    if (nothingSouth) {
        MeshBuilder wall;
        wall.addBox(origin + glm::vec3(0.0f, 0.0f, kRoomSide), origin + glm::vec3(kRoomSide, kWallHeight, kRoomSide + kWallThickness));
        addObject(scene, "south wall", wall, kPlaster);
    }

    // The furniture, one piece per cell of a shuffled 4 x 4 grid (Fisher-Yates).
    std::array<uint32_t, kCellsPerSide * kCellsPerSide> cells{};
    for (uint32_t i = 0; i < cells.size(); ++i) cells[i] = i;
    for (uint32_t i = uint32_t(cells.size()) - 1; i > 0; --i) std::swap(cells[i], cells[randomIndex(random, i + 1)]);
    uint32_t nextCell = 0;
    auto cellCentre = [&]() {
        const uint32_t cell = cells[nextCell++];
        return origin + glm::vec3((float(cell % kCellsPerSide) + 0.5f) * kCellSide, 0.0f,
                                  (float(cell / kCellsPerSide) + 0.5f) * kCellSide);
    };
    auto randomFacing = [&]() { return glm::vec2(random.uniform(0.3f, 1.0f), random.uniform(-1.0f, 1.0f)); };

    MeshBuilder columnMesh;
    columnMesh.addLathe(kColumnProfile, layout.segments);
    addObject(scene, "column", columnMesh, kStone, placed(cellCentre(), {1.0f, 0.0f}));
    const glm::vec3 tableAt = cellCentre();
    addObject(scene, "table", table(), kDarkWood, placed(tableAt, randomFacing()));
    MeshBuilder vase;
    vase.addLathe(vaseProfile(layout.rings), layout.segments);
    addObject(scene, "vase", vase, kGlaze, placed(tableAt + glm::vec3(random.uniform(-0.3f, 0.3f), 0.78f, 0.0f), {1.0f, 0.0f}));
    MeshBuilder barrel;
    barrel.addLathe(barrelProfile(layout.rings), layout.segments);
    addObject(scene, "barrel", barrel, kSteel, placed(cellCentre(), {1.0f, 0.0f}));
    const glm::vec3 planterAt = cellCentre();
    MeshBuilder planter;
    planter.addBox({-0.4f, 0.0f, -0.4f}, {0.4f, 0.5f, 0.4f});
    addObject(scene, "planter", planter, kTerracotta, placed(planterAt, randomFacing()));
    addObject(scene, "foliage", foliageCards(0.5f), kFoliage, placed(planterAt, randomFacing()));
    for (uint32_t i = 0; i < layout.cratesPerRoom; ++i) {
        const float side = random.uniform(0.5f, 1.0f);
        MeshBuilder crate;
        crate.addBox({-0.5f * side, 0.0f, -0.5f * side}, {0.5f * side, random.uniform(0.5f, 1.0f), 0.5f * side});
        addObject(scene, "crate", crate, kCrateWood, placed(cellCentre(), randomFacing()));
    }
}

// ---- camera ----------------------------------------------------------------------------------

// Above the grid a fifth of the way along its diagonal, looking down it at a point four fifths
// along, from a height that grows with the grid: about 30 degrees down for one room, 17 for the
// largest. The rooms behind and beside the eye are out of view (what per-view culling skips).
void addCamera(Scene& scene, const Layout& layout) {
    const glm::vec2 extent(float(layout.columns) * kRoomSide, float(layout.rows) * kRoomSide);
    const float height = 2.0f + 0.25f * std::max(extent.x, extent.y);
    Camera& camera = scene.camera;
    camera.name = "rooms";
    camera.view = glm::lookAtRH(glm::vec3(0.2f * extent.x, height, 0.2f * extent.y),
                                glm::vec3(0.8f * extent.x, 0.0f, 0.8f * extent.y), glm::vec3(0.0f, 1.0f, 0.0f));
    camera.yfov = 1.04719755f;  // 60 degrees
    camera.znear = 0.1f;
    camera.zfar = farthestViewDepth(scene.bounds, camera.view) + 1.0f;
    scene.cameraFromFile = true;
}

// ---- lights ----------------------------------------------------------------------------------

constexpr float kDegree = 0.0174532925f;
constexpr uint32_t kSpots = 64;
constexpr uint32_t kPoints = 32;
constexpr float kDesignAspect = 16.0f / 9.0f;

// Inside |x|, |y| <= margin in NDC of the 16:9, 60 degree view, in front of the eye. The
// projection by hand: 1/tan(30 deg) = sqrt(3), so no tan() can move a light by a last bit.
bool insideView(const Camera& camera, const glm::vec3& p, float margin) {
    const glm::vec3 v(camera.view * glm::vec4(p, 1.0f));
    const float depth = -v.z;
    const float focal = std::sqrt(3.0f);
    return depth > 0.5f && depth < camera.zfar && std::abs(focal / kDesignAspect * v.x) <= margin * depth &&
           std::abs(focal * v.y) <= margin * depth;
}

// 64 spots and 32 points spread evenly over the rooms whose middle the camera sees, each at an
// inner corner of the room's furniture cells (clear of every piece: the pieces stand at cell
// centres and reach at most 0.83 m from them, the corners lie 1.41 m away). Spots hang 2.7 m up
// and shine down, tilted up to ~17 degrees; points float 1.6-2.4 m up. The more lights share a
// room, the dimmer each, so a frame is about as bright whatever the size.
void addLamps(Scene& scene, const Layout& layout) {
    std::vector<uint32_t> visible;
    for (uint32_t room = 0; room < layout.rooms; ++room) {
        const glm::vec3 middle((float(room % layout.columns) + 0.5f) * kRoomSide, 1.0f,
                               (float(room / layout.columns) + 0.5f) * kRoomSide);
        if (insideView(scene.camera, middle, 0.85f)) visible.push_back(room);
    }
    if (visible.empty()) {
        for (uint32_t room = 0; room < layout.rooms; ++room) visible.push_back(room);
    }
    const float lightsPerRoom = float(kSpots + kPoints) / float(visible.size());
    const float dimming = std::min(1.0f, 3.0f / lightsPerRoom);
    PortableRandom random(0x6C616D7073ull);  // "lamps"
    for (uint32_t i = 0; i < kSpots + kPoints; ++i) {
        const bool spot = i < kSpots;
        const uint32_t room = visible[size_t(i) * visible.size() / (kSpots + kPoints)];
        const glm::vec3 origin(float(room % layout.columns) * kRoomSide, 0.0f, float(room / layout.columns) * kRoomSide);
        Light light;
        light.name = (spot ? "spot " : "point ") + std::to_string(i);
        light.type = spot ? LightType::Spot : LightType::Point;
        light.color = randomLightColor(random);
        light.castsShadow = true;
        // An inner cell corner of the room whose lamp the camera sees (the room's middle is in
        // view, not necessarily each corner): the first of up to 16 random ones.
        const float height = spot ? 2.7f : random.uniform(1.6f, 2.4f);
        glm::vec3 lamp(0.0f);
        for (int attempt = 0; attempt < 16; ++attempt) {
            lamp = origin + glm::vec3(kCellSide * float(1 + randomIndex(random, 3)), height,
                                      kCellSide * float(1 + randomIndex(random, 3)));
            if (insideView(scene.camera, lamp, 0.95f)) break;
        }
        light.position = lamp;
        if (spot) {
            light.direction = glm::normalize(glm::vec3(random.uniform(-0.3f, 0.3f), -1.0f, random.uniform(-0.3f, 0.3f)));
            light.outerConeAngle = random.uniform(35.0f, 55.0f) * kDegree;
            light.innerConeAngle = 0.6f * light.outerConeAngle;
            light.range = 7.0f;
            light.intensity = intensityForIlluminance(random.uniform(1.5f, 3.0f) * dimming, 2.7f, light.range);
        } else {
            light.range = 5.0f;
            light.intensity = intensityForIlluminance(random.uniform(1.0f, 2.0f) * dimming, 2.0f, light.range);
        }
        scene.lights.push_back(light);
    }
    // A dim sun from high up (about 60 degrees), so the rooms the lamps miss still show.
    Light sun;
    sun.name = "sun";
    sun.type = LightType::Directional;
    sun.direction = glm::normalize(glm::vec3(-0.45f, -1.0f, -0.3f));
    sun.color = glm::vec3(1.0f, 0.96f, 0.9f);
    sun.intensity = 0.6f;
    sun.castsShadow = true;
    scene.lights.push_back(sun);
}

}  // namespace
}  // namespace rooms_scene

Scene makeRoomsScene(uint64_t targetTriangles) {
    using namespace rooms_scene;
    const Layout layout = layoutFor(targetTriangles);
    Scene scene;
    scene.source = kSource;
    // Reserved up front: growth by doubling would hold up to twice the scene for a moment. Lathes
    // have about half a vertex per triangle, boxes two; 0.7 covers every size.
    scene.indices.reserve(size_t(layout.triangles) * 3);
    scene.vertices.reserve(size_t(double(layout.triangles) * 0.7));
    addMaterials(scene);
    PortableRandom random(0x726F6F6D73ull);  // "rooms"
    for (uint32_t room = 0; room < layout.rooms; ++room) addRoom(scene, layout, room, random);
    scene.computeBounds();
    addCamera(scene, layout);
    addLamps(scene, layout);
    return scene;
}

}  // namespace punctual
