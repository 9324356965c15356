// What the report counts: its rows (kinds of object) and the reasons an object was dropped or
// noted. Enums, so a misspelt row or reason does not compile; their printed texts are in one
// table each (report_reasons.cpp).
#pragma once

#include <cstddef>

namespace citygen {

// The rows of the report, grouped by the stage that first counts them.
enum class ReportKind {
    // read_osm
    MappedTrees,
    RoadMarkNodes,
    TaggedStreetLamps,
    HighwayWays,
    CoastlineWays,
    TreeRows,
    RailwayWays,
    BuildingWays,
    BuildingRelations,
    BuildingAreas,
    LandCoverAreas,
    // buildings, heights, colours, roofs
    Buildings,
    BuildingParts,
    BuildingHoles,
    BuildingHeights,
    ColoursAndMaterials,
    Roofs,
    // roads
    RoadWays,
    RoadEdges,
    RoadJoints,
    RoadLanes,
    ZebraCrossings,
    StopLines,
    SidewalkSides,
    SidewalkStrips,
    SidewalkCorners,
    // paths, then one row per PathClass (path_class_row)
    PathWays,
    PathEdges,
    PathJoints,
    PathFootway,
    PathPath,
    PathCycleway,
    PathPedestrian,
    PathSteps,
    PathTrack,
    PathBridleway,
    PathRail,
    PathTram,
    PathLightRail,
    PathSubway,
    // land cover: one row per LandCoverClass (land_cover_row), then the holes
    LandCoverWater,
    LandCoverSea,
    LandCoverGreen,
    LandCoverForest,
    LandCoverPaved,
    LandCoverSand,
    LandCoverFarmland,
    LandCoverBuiltUp,
    LandCoverAreaHoles,
    // sea
    SeaPolygons,
    SeaPolygonHoles,
    CoastlineIslands,
    CoastlineIslandHoles,
    // lamps, trees, generated buildings
    GeneratedStreetLamps,
    TreeRowTrees,
    ForestTrees,
    GeneratedBuildings,
    // terrain (--dem)
    DemFiles,
    TerrainNodes,
    // --keep-inside: what the tile keeps of what it parsed (osmparse/tiles/keep_inside_box.h)
    TileBuildings,
    TileRoadEdges,
    TileRoadJoints,
    TileSidewalks,
    TilePathEdges,
    TilePathJoints,
    TileCrossings,
    TileLamps,
    TileLandCover,
    TileTrees,
    Count  // not a row: the number of rows
};

// Why an object was dropped, or what was changed or guessed about it (a note), grouped by the
// stage that reports it; a reason several stages give is listed under the first.
enum class ReportReason {
    // read_osm
    InvalidLocation,
    NodesMissing,
    ClippedAtEdge,
    NotClosed,
    OutlinePassedForRepair,
    CouldNotAssemble,
    MembersMissing,
    RelationMembersMissing,
    // clean_footprint
    Degenerate,
    Unrepairable,
    Repaired,
    HoleBelowMinArea,
    HoleOutside,
    HoleOverlaps,
    SliverBelowMinArea,
    InvalidAtOutput,
    // build_buildings
    IgnoredType,
    ReplacedByParts,
    PartOutsideOutline,
    TooManyPoints,
    TooLarge,
    FarFromOrigin,
    // building_height: one per height tag, then the rules
    BadHeightTag,
    BadLevelsTag,
    BadMinHeightTag,
    BadMinLevelTag,
    ZeroHeightIgnored,
    HeightFromHeightTag,
    HeightFromLevels,
    RandomHeight,
    MinHeightNotBelowHeight,
    // infer_heights
    LandUseTooLarge,
    FromTypeAndArea,
    FromTypeAreaAndLandUse,
    FromSurroundings,
    PointBlock,
    Twin,
    LandmarkHome,
    Calibrated,
    FromTaggedNeighbours,
    FromExtractMedian,
    FromDisagreeingNeighbours,
    NoHeightRule,
    // choose_colours_and_materials
    UnknownWallMaterial,
    UnknownRoofMaterial,
    WallColourTagged,
    BadWallColour,
    RoofColourTagged,
    BadRoofColour,
    // build_roofs: the tags, why no roof was built (make_roof_faces), then per RoofShape
    // (roof_shape_notes) the shape built as tagged or by default, its faces failing the checks,
    // and a shape built hipped instead
    UnknownRoofShape,
    BadRoofAngle,
    BadRoofDirection,
    BadRoofHeight,
    RoofHeightClamped,
    RoofTooLow,
    RoofDegenerateFootprint,
    RoofSkeletonFailed,
    RoofUnknownShape,
    RoofFlatTagged,
    RoofFlatDefault,
    RoofSkillionTagged,
    RoofSkillionDefault,
    RoofSkillionFailedChecks,
    RoofSkillionBuiltHipped,
    RoofGabledTagged,
    RoofGabledDefault,
    RoofGabledFailedChecks,
    RoofGabledBuiltHipped,
    RoofHippedTagged,
    RoofHippedDefault,
    RoofHippedFailedChecks,
    RoofHalfHippedTagged,
    RoofHalfHippedDefault,
    RoofHalfHippedFailedChecks,
    RoofHalfHippedBuiltHipped,
    RoofPyramidalTagged,
    RoofPyramidalDefault,
    RoofPyramidalFailedChecks,
    RoofPyramidalBuiltHipped,
    RoofGambrelTagged,
    RoofGambrelDefault,
    RoofGambrelFailedChecks,
    RoofGambrelBuiltHipped,
    RoofMansardTagged,
    RoofMansardDefault,
    RoofMansardFailedChecks,
    RoofMansardBuiltHipped,
    RoofDomeTagged,
    RoofDomeDefault,
    RoofDomeFailedChecks,
    RoofDomeBuiltHipped,
    RoofOnionTagged,
    RoofOnionDefault,
    RoofOnionFailedChecks,
    RoofOnionBuiltHipped,
    RoofRoundTagged,
    RoofRoundDefault,
    RoofRoundFailedChecks,
    RoofRoundBuiltHipped,
    // build_road_graph (carriageway_exclusion, road_width)
    NotAHighway,
    NotACarriagewayClass,
    AreaYes,
    Tunnel,
    WidthTagUnusable,
    LanesTagUnusable,
    ZeroLength,
    Over5Km,
    DuplicatePiece,
    NoPieceLeft,
    MergedCollinear,
    // build_road_polygons
    AbsorbedIntoMergedJunction,
    TooShortForJunctions,
    NothingLeftOfJoint,
    MergedFromNearbyJunctions,
    StarOrHullJoint,
    HoleBeyondQuadEnd,
    QuadOverlapsJoint,
    // narrow_roads
    NarrowerThanMinWidth,
    NarrowedBesideBuilding,
    // lay_out_lanes: one per lane count tag, then the road marks
    LaneCountUnusable,
    ForwardLaneCountUnusable,
    BackwardLaneCountUnusable,
    OnJunctionPolygon,
    NotOnDrawnRoad,
    // build_sidewalks
    NoRoomBesideBuilding,
    DegenerateTangledJunction,
    OverlapsBuilding,
    TrimmedOffRoad,
    LiesOnAnotherRoad,
    // build_paths
    AreaOrIndoor,
    ReplacedByMappedSidewalk,
    // build_land_cover
    BeyondSceneLimits,
    ClippedAtSceneLimits,
    // assemble_sea
    CoastlineEndsInside,
    CoastlineDirectionsDisagree,
    CoastlineDoesNotClose,
    IslandNotInSea,
    TwoWaysStartAtOneNode,
    CutByExtract,
    WouldFloodCity,
    BuildingsInSea,
    // place_lamps
    MovedOffRoad,
    InsideRoadOrBuilding,
    // place_trees: one per tree tag, then the placement
    TreeHeightUnusable,
    TreeEstHeightUnusable,
    CrownDiameterUnusable,
    InBuildingRoadOrWater,
    OnRoadBuildingOrWater,
    ForestCapReached,
    // fill_empty_blocks
    BlockNotBuiltUp,
    BlockSizeOutOfRange,
    BlockFilled,
    LotWithoutAccess,
    LotTooSmall,
    LotOverlaps,
    // build_terrain: the DEMs (read_dem), then the nodes (fill_dem_voids)
    DemOutsideExtract,
    DemHeightsInFeet,
    DemVerticalDatumAssumed,
    DemVerticalDatumNamed,
    DemHeightsAboveEllipsoid,
    TerrainVoidFilled,
    TerrainVoidAtCoast,
    TerrainOutsideEveryDem,
    TerrainHeightBeyondLimits,
    // keep_inside_box
    AnchorInAnotherTile,
    Count  // not a reason: the number of reasons
};

inline constexpr size_t kReportKindCount = static_cast<size_t>(ReportKind::Count);
inline constexpr size_t kReportReasonCount = static_cast<size_t>(ReportReason::Count);

// The printed texts (e.g. "building parts", "sliver below min area").
const char* text_of(ReportKind kind);
const char* text_of(ReportReason reason);

}  // namespace citygen
