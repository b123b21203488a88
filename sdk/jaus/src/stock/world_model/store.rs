//! [`VectorStore`]: the objects, their spatial index and feature-class index, the
//! feature-class metadata, and the limits ([`StoreConfig`]) that bound its memory.
//!
//! # Spatial index
//!
//! Objects are indexed in **degrees**: every object puts the bounding box of its
//! vertices, in (latitude, unwrapped longitude), widened by its buffer converted to
//! degrees with the smallest metres-per-degree the distance frame of
//! [`geometry`](super::geometry) can use (the meridian radius at the equator for
//! latitude; the equatorial radius times the cosine of the highest latitude the box
//! reaches for longitude), into an [`rstar`] R*-tree. A box that crosses the
//! antimeridian is entered once more shifted by 360°. A region query widens the
//! region's box by the region buffer the same way, collects the objects whose boxes
//! intersect it (never a scan of every object) and runs the exact test of
//! [`geometry`](super::geometry) on each; the widening is conservative for the frame, so the index never drops an object
//! the exact test would keep ([`VectorStore::query_linear`] is the scan used to check
//! that, and the baseline of `benches/world_model.rs`).
//!
//! # Bounds on memory
//!
//! [`StoreConfig`] limits the number of objects, the vertices of one object and of the
//! whole store, the buffer, the feature classes of an object and the metadata text;
//! what exceeds a limit is refused with a [`StoreError`] naming that limit.

use std::collections::{BTreeMap, BTreeSet, HashMap};

use rstar::RTree;

use super::coords::Box4;
use super::error::StoreError;
use super::geometry::{analyse, Shape, View, MAX_VERTICES};
use super::index::Entry;
pub use super::region::ObjectId;
use super::region::{class_matches, sorted_ids, within, Filter};
use crate::messages::{VksMetadataOption, VksObject, VksStoredObject};

/// Limits of a [`VectorStore`].
#[derive(Debug, Clone, PartialEq)]
pub struct StoreConfig {
    /// Most objects stored at once.
    pub max_objects: usize,
    /// Most vertices of one object (at most [`MAX_VERTICES`]; larger values are taken
    /// as [`MAX_VERTICES`]).
    pub max_vertices: usize,
    /// Most vertices of all objects together.
    pub max_total_vertices: usize,
    /// Largest region buffer of a stored object, metres.
    pub max_buffer: f32,
    /// Most feature classes of one object (the wire allows 255).
    pub max_feature_classes: usize,
    /// Most bytes of feature-class metadata text, all classes together (one class holds
    /// at most 65,535, the u16 length of the wire).
    pub max_metadata_bytes: usize,
}

impl Default for StoreConfig {
    fn default() -> Self {
        Self {
            max_objects: 1 << 20,
            max_vertices: MAX_VERTICES,
            max_total_vertices: 1 << 24,
            max_buffer: 1.0e6,
            max_feature_classes: 255,
            max_metadata_bytes: 1 << 22,
        }
    }
}

#[derive(Debug, Clone)]
struct Stored {
    object: VksStoredObject,
    shape: Shape,
    shift: f64,
    fp: Box4,
}

impl Stored {
    fn view(&self) -> View<'_> {
        View {
            shape: self.shape,
            points: &self.object.points,
            shift: self.shift,
            fp: self.fp,
        }
    }

    fn index_boxes(&self) -> impl Iterator<Item = Box4> {
        self.fp.expand(f64::from(self.object.buffer)).index_boxes()
    }
}

/// The bounding box of stored objects' vertices, degrees. `west > east` when the box
/// crosses the antimeridian.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Bounds {
    /// Southernmost latitude.
    pub south: f64,
    /// Western edge longitude.
    pub west: f64,
    /// Northernmost latitude.
    pub north: f64,
    /// Eastern edge longitude.
    pub east: f64,
}

/// Vector objects in WGS 84 with feature classes, a spatial index and feature-class
/// metadata. No I/O; every operation is bounded by its [`StoreConfig`].
#[derive(Debug)]
pub struct VectorStore {
    config: StoreConfig,
    /// Object ID → slot (ordered, for listings by ID).
    objects: BTreeMap<ObjectId, u32>,
    /// The objects; the index entries point here, so a region query reads no map.
    slots: Vec<Option<Stored>>,
    /// Empty slots.
    free: Vec<u32>,
    tree: RTree<Entry>,
    classes: HashMap<u16, BTreeSet<ObjectId>>,
    metadata: BTreeMap<u16, String>,
    metadata_bytes: usize,
    total_vertices: usize,
    next_id: ObjectId,
}

impl Default for VectorStore {
    fn default() -> Self {
        Self::new(StoreConfig::default())
    }
}

impl VectorStore {
    /// An empty store with these limits.
    pub fn new(mut config: StoreConfig) -> Self {
        config.max_vertices = config.max_vertices.min(MAX_VERTICES);
        Self {
            config,
            objects: BTreeMap::new(),
            slots: Vec::new(),
            free: Vec::new(),
            tree: RTree::new(),
            classes: HashMap::new(),
            metadata: BTreeMap::new(),
            metadata_bytes: 0,
            total_vertices: 0,
            next_id: 1,
        }
    }

    /// The limits.
    pub fn config(&self) -> &StoreConfig {
        &self.config
    }

    /// Number of objects.
    pub fn len(&self) -> usize {
        self.objects.len()
    }

    /// Whether the store holds no object.
    pub fn is_empty(&self) -> bool {
        self.objects.is_empty()
    }

    /// Vertices of all objects.
    pub fn total_vertices(&self) -> usize {
        self.total_vertices
    }

    /// The object with this ID.
    pub fn get(&self, id: ObjectId) -> Option<&VksStoredObject> {
        self.stored(id).map(|s| &s.object)
    }

    fn stored(&self, id: ObjectId) -> Option<&Stored> {
        self.objects.get(&id).and_then(|&slot| self.slot(slot))
    }

    fn slot(&self, slot: u32) -> Option<&Stored> {
        self.slots.get(slot as usize).and_then(Option::as_ref)
    }

    /// The IDs of all objects, ascending.
    pub fn ids(&self) -> impl Iterator<Item = ObjectId> + '_ {
        self.objects.keys().copied()
    }

    /// Stores an object (its buffer is 0 when `None`) and returns the ID it gets: never
    /// 0, never that of another stored object.
    pub fn create(&mut self, object: &VksObject) -> Result<ObjectId, StoreError> {
        let (id, slot) = self.admit(object)?;
        if let Some(stored) = &self.slots[slot as usize] {
            for b in stored.index_boxes() {
                self.tree.insert(Entry {
                    slot,
                    env: b.aabb(),
                });
            }
        }
        Ok(id)
    }

    /// Validates and stores an object without indexing it: its ID and slot.
    fn admit(&mut self, object: &VksObject) -> Result<(ObjectId, u32), StoreError> {
        self.admit_as(object, None)
    }

    /// [`admit`](Self::admit) under a given ID (`Some`: one not in use and not 0,
    /// checked by the caller) or the next free one (`None`).
    fn admit_as(
        &mut self,
        object: &VksObject,
        given: Option<ObjectId>,
    ) -> Result<(ObjectId, u32), StoreError> {
        let c = &self.config;
        if self.objects.len() >= c.max_objects {
            return Err(StoreError::TooManyObjects { max: c.max_objects });
        }
        let shape = Shape::from_wire(object.object_type)?;
        let n = object.points.len();
        if n > c.max_vertices {
            return Err(StoreError::TooManyVertices {
                count: n,
                max: c.max_vertices,
            });
        }
        if self.total_vertices + n > c.max_total_vertices {
            return Err(StoreError::TotalVertices {
                count: n,
                max: c.max_total_vertices,
            });
        }
        if object.feature_classes.len() > c.max_feature_classes {
            return Err(StoreError::TooManyFeatureClasses {
                count: object.feature_classes.len(),
                max: c.max_feature_classes,
            });
        }
        let buffer = object.buffer.unwrap_or(0.0);
        if !(0.0..=c.max_buffer).contains(&buffer) {
            return Err(StoreError::Buffer {
                value: f64::from(buffer),
                max: f64::from(c.max_buffer),
            });
        }
        let (fp, shift) = analyse(shape, &object.points, c.max_vertices)?;
        let id = match given {
            Some(id) => id,
            None => self.free_id(),
        };
        let stored = Stored {
            object: VksStoredObject {
                object_id: id,
                object_type: shape.to_wire(),
                buffer,
                feature_classes: object.feature_classes.clone(),
                points: object.points.clone(),
            },
            shape,
            shift,
            fp,
        };
        // Slots never outnumber `max_objects` (< 2³²), so a slot fits in a u32.
        let slot = match self.free.pop() {
            Some(slot) => slot,
            None => {
                self.slots.push(None);
                (self.slots.len() - 1) as u32
            }
        };
        for f in &object.feature_classes {
            self.classes.entry(f.id).or_default().insert(id);
        }
        self.total_vertices += n;
        self.objects.insert(id, slot);
        self.slots[slot as usize] = Some(stored);
        Ok((id, slot))
    }

    fn free_id(&mut self) -> ObjectId {
        // At most `max_objects` (< 2³² − 1) IDs are taken, so this ends.
        loop {
            let id = self.next_id;
            self.next_id = if id == u32::MAX { 1 } else { id + 1 };
            if !self.objects.contains_key(&id) {
                return id;
            }
        }
    }

    /// Stores every object; the result of each, in order (an object refused does not
    /// stop the others). A batch at least as large as the store indexes by bulk loading:
    /// the R*-tree is rebuilt from every entry at once (the OMT packing of `rstar`),
    /// several times faster than one insertion per object; a smaller batch is inserted
    /// entry by entry. Queries give the same answers either way.
    pub fn create_all<'a>(
        &mut self,
        objects: impl IntoIterator<Item = &'a VksObject>,
    ) -> Vec<Result<ObjectId, StoreError>> {
        let mut results = Vec::new();
        let mut admitted = Vec::new();
        for o in objects {
            let r = self.admit(o);
            if let Ok((_, slot)) = r {
                admitted.push(slot);
            }
            results.push(r.map(|(id, _)| id));
        }
        let entries = |slots: &[Option<Stored>], list: &[u32]| -> Vec<Entry> {
            list.iter()
                .filter_map(|&slot| slots[slot as usize].as_ref().map(|s| (slot, s)))
                .flat_map(|(slot, s)| {
                    s.index_boxes().map(move |b| Entry {
                        slot,
                        env: b.aabb(),
                    })
                })
                .collect()
        };
        let new = entries(&self.slots, &admitted);
        if new.len() >= self.tree.size() {
            let mut all: Vec<Entry> = std::mem::take(&mut self.tree).into_iter().collect();
            all.extend(new);
            self.tree = RTree::bulk_load(all);
        } else {
            for e in new {
                self.tree.insert(e);
            }
        }
        results
    }

    /// A store with these limits holding `objects` under their own IDs (a store
    /// rebuilt from what a journal committed: the same checks as
    /// [`create`](Self::create), indexed by bulk loading). New IDs continue after the
    /// highest restored one. Refused: an ID of 0 or given twice, or an object the
    /// limits refuse (the error names its ID).
    pub fn restore(
        config: StoreConfig,
        objects: impl IntoIterator<Item = VksStoredObject>,
    ) -> Result<Self, (ObjectId, StoreError)> {
        let mut store = Self::new(config);
        let mut highest = 0;
        for o in objects {
            let id = o.object_id;
            if id == 0 || store.objects.contains_key(&id) {
                return Err((id, StoreError::Restore("an object ID of 0 or given twice")));
            }
            let object = VksObject {
                object_type: o.object_type,
                buffer: Some(o.buffer),
                feature_classes: o.feature_classes,
                points: o.points,
            };
            store.admit_as(&object, Some(id)).map_err(|e| (id, e))?;
            highest = highest.max(id);
        }
        store.next_id = if highest == u32::MAX { 1 } else { highest + 1 };
        let entries: Vec<Entry> = store
            .slots
            .iter()
            .enumerate()
            .filter_map(|(slot, s)| s.as_ref().map(|s| (slot as u32, s)))
            .flat_map(|(slot, s)| {
                s.index_boxes().map(move |b| Entry {
                    slot,
                    env: b.aabb(),
                })
            })
            .collect();
        store.tree = RTree::bulk_load(entries);
        Ok(store)
    }

    /// The ID the next object created gets unless it is in use.
    pub fn next_id(&self) -> ObjectId {
        self.next_id
    }

    /// Every feature class with metadata text, and its text, by class.
    pub fn all_metadata(&self) -> impl Iterator<Item = (u16, &str)> + '_ {
        self.metadata.iter().map(|(c, t)| (*c, t.as_str()))
    }

    /// Deletes the objects with these IDs (unknown IDs are ignored); returns how many
    /// were deleted.
    pub fn delete(&mut self, ids: &[ObjectId]) -> usize {
        ids.iter().filter(|id| self.remove(**id)).count()
    }

    fn remove(&mut self, id: ObjectId) -> bool {
        let Some(slot) = self.objects.remove(&id) else {
            return false;
        };
        let Some(s) = self.slots.get_mut(slot as usize).and_then(Option::take) else {
            return false;
        };
        self.free.push(slot);
        for b in s.index_boxes() {
            self.tree.remove(&Entry {
                slot,
                env: b.aabb(),
            });
        }
        for f in &s.object.feature_classes {
            if let Some(set) = self.classes.get_mut(&f.id) {
                set.remove(&id);
                if set.is_empty() {
                    self.classes.remove(&f.id);
                }
            }
        }
        self.total_vertices -= s.object.points.len();
        true
    }

    /// Deletes the objects a filter selects; refused for a filter with no criterion.
    /// Returns the IDs deleted.
    pub fn delete_matching(&mut self, filter: &Filter) -> Result<Vec<ObjectId>, StoreError> {
        if filter.is_empty() {
            return Err(StoreError::EmptyFilter);
        }
        let ids = self.query(filter);
        self.delete(&ids);
        Ok(ids)
    }

    /// Deletes every object (metadata stays).
    pub fn clear(&mut self) {
        self.objects.clear();
        self.slots.clear();
        self.free.clear();
        self.tree = RTree::new();
        self.classes.clear();
        self.total_vertices = 0;
    }

    /// The IDs of the objects a filter selects, ascending. A region is looked up in the
    /// spatial index; feature-class IDs in the class index; only a filter with neither
    /// reads every object.
    pub fn query(&self, filter: &Filter) -> Vec<ObjectId> {
        let filter = &*sorted_ids(filter);
        let keep = |s: &&Stored| self.matches(s, filter);
        if let Some(ids) = &filter.ids {
            // Sorted already.
            return ids
                .iter()
                .filter_map(|id| self.stored(*id))
                .filter(keep)
                .map(|s| s.object.object_id)
                .collect();
        }
        let mut ids: Vec<ObjectId> = if let Some(r) = &filter.region {
            let mut slots = Vec::new();
            for b in r.query_boxes() {
                slots.extend(
                    self.tree
                        .locate_in_envelope_intersecting(&b.aabb())
                        .map(|e| e.slot),
                );
            }
            // An object crossing the antimeridian has two entries.
            slots.sort_unstable();
            slots.dedup();
            slots
                .into_iter()
                .filter_map(|slot| self.slot(slot))
                .filter(keep)
                .map(|s| s.object.object_id)
                .collect()
        } else if let Some(c) = filter
            .classes
            .as_ref()
            .filter(|c| c.iter().all(|f| f.id.is_some()))
        {
            let mut v: Vec<ObjectId> = c
                .iter()
                .filter_map(|f| f.id.and_then(|id| self.classes.get(&id)))
                .flatten()
                .copied()
                .collect();
            v.sort_unstable();
            v.dedup();
            return v
                .into_iter()
                .filter_map(|id| self.stored(id))
                .filter(keep)
                .map(|s| s.object.object_id)
                .collect();
        } else {
            return self.query_linear(filter);
        };
        ids.sort_unstable();
        ids
    }

    /// The same as [`query`](Self::query) by reading every object (no index): the
    /// reference the index is checked and measured against.
    pub fn query_linear(&self, filter: &Filter) -> Vec<ObjectId> {
        let filter = &*sorted_ids(filter);
        let mut ids: Vec<ObjectId> = self
            .slots
            .iter()
            .flatten()
            .filter(|s| self.matches(s, filter))
            .map(|s| s.object.object_id)
            .collect();
        ids.sort_unstable();
        ids
    }

    fn matches(&self, s: &Stored, f: &Filter) -> bool {
        if let Some(ids) = &f.ids {
            if ids.binary_search(&s.object.object_id).is_err() {
                return false;
            }
        }
        if let Some(c) = &f.classes {
            if !class_matches(&s.object, c) {
                return false;
            }
        }
        if let Some(r) = &f.region {
            if !within(&s.view(), r, f64::from(s.object.buffer) + r.buffer()) {
                return false;
            }
        }
        true
    }

    /// The bounding box of the vertices of every object (`class: None`) or of the
    /// objects in a feature class; `None` when there is none. Reads the objects
    /// selected (the whole store for `None`).
    pub fn bounds(&self, class: Option<u16>) -> Option<Bounds> {
        let fps: Vec<Box4> = match class {
            None => self.slots.iter().flatten().map(|s| s.fp).collect(),
            Some(c) => self
                .classes
                .get(&c)?
                .iter()
                .filter_map(|id| self.stored(*id).map(|s| s.fp))
                .collect(),
        };
        let south = fps.iter().map(|b| b.lat_lo).fold(f64::INFINITY, f64::min);
        let north = fps
            .iter()
            .map(|b| b.lat_hi)
            .fold(f64::NEG_INFINITY, f64::max);
        if fps.is_empty() {
            return None;
        }
        // Longitude: the shortest arc covering every object, i.e. the complement of the
        // largest gap between the merged longitude intervals on the circle. When the
        // objects span at most 180° without crossing ±180°, the gap round the back is
        // the largest: no sorting needed.
        let west = fps.iter().map(|b| b.lon_lo).fold(f64::INFINITY, f64::min);
        let east = fps
            .iter()
            .map(|b| b.lon_hi)
            .fold(f64::NEG_INFINITY, f64::max);
        if east <= 180.0 && east - west <= 180.0 {
            return Some(Bounds {
                south,
                west,
                north,
                east,
            });
        }
        let mut pieces: Vec<(f64, f64)> = Vec::with_capacity(fps.len() + 1);
        for b in &fps {
            pieces.push((b.lon_lo, b.lon_hi.min(180.0)));
            if b.lon_hi > 180.0 {
                pieces.push((-180.0, b.lon_hi - 360.0));
            }
        }
        pieces.sort_by(|a, b| a.0.total_cmp(&b.0));
        let mut merged: Vec<(f64, f64)> = Vec::new();
        for (lo, hi) in pieces {
            match merged.last_mut() {
                Some(last) if lo <= last.1 => last.1 = last.1.max(hi),
                _ => merged.push((lo, hi)),
            }
        }
        let (first, last) = (merged[0], merged[merged.len() - 1]);
        let mut best = (first.0 + 360.0 - last.1, first.0, last.1);
        for w in merged.windows(2) {
            let gap = w[1].0 - w[0].1;
            if gap > best.0 {
                best = (gap, w[1].0, w[0].1);
            }
        }
        let (west, east) = if best.0 <= 0.0 {
            (-180.0, 180.0)
        } else {
            (best.1, best.2)
        };
        Some(Bounds {
            south,
            west,
            north,
            east,
        })
    }

    /// Changes the metadata text of a feature class.
    pub fn set_metadata(
        &mut self,
        class: u16,
        option: VksMetadataOption,
        text: &str,
    ) -> Result<(), StoreError> {
        let old = self.metadata.get(&class).map_or("", String::as_str);
        let new = match option {
            VksMetadataOption::Append => format!("{old}{text}"),
            VksMetadataOption::Prepend => format!("{text}{old}"),
            VksMetadataOption::Overwrite => text.to_string(),
            VksMetadataOption::Erase => String::new(),
            VksMetadataOption::Unknown(v) => return Err(StoreError::MetadataOption(v)),
        };
        if new.len() > usize::from(u16::MAX) {
            return Err(StoreError::MetadataTooLong {
                class,
                len: new.len(),
            });
        }
        let total = self.metadata_bytes - old.len() + new.len();
        if total > self.config.max_metadata_bytes {
            return Err(StoreError::MetadataFull {
                total,
                max: self.config.max_metadata_bytes,
            });
        }
        self.metadata_bytes = total;
        if new.is_empty() {
            self.metadata.remove(&class);
        } else {
            self.metadata.insert(class, new);
        }
        Ok(())
    }

    /// The metadata text of a feature class (empty when none was set).
    pub fn metadata(&self, class: u16) -> &str {
        self.metadata.get(&class).map_or("", String::as_str)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::messages::{VksObjectType, VksPoint};

    fn point(lat: f64, lon: f64) -> VksObject {
        VksObject {
            object_type: VksObjectType::Point,
            buffer: None,
            feature_classes: vec![],
            points: vec![VksPoint {
                latitude: lat,
                longitude: lon,
            }],
        }
    }

    #[test]
    fn ids_wrap_round_and_skip_those_in_use() {
        let mut s = VectorStore::default();
        assert_eq!(s.create(&point(0.0, 0.0)), Ok(1));
        s.next_id = u32::MAX;
        assert_eq!(s.create(&point(0.0, 0.0)), Ok(u32::MAX));
        // 0 is never given; 1 is in use.
        assert_eq!(s.create(&point(0.0, 0.0)), Ok(2));
        assert_eq!(s.delete(&[1]), 1);
        s.next_id = u32::MAX;
        assert_eq!(s.create(&point(0.0, 0.0)), Ok(1));
        // Slots are reused: three objects, three slots.
        assert_eq!(s.slots.len(), 3);
        assert!(s.free.is_empty());
    }
}
