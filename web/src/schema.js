// The scene file's keys as `coinroll schema` prints them (embedded at build time), and the scene
// object read and written by those keys' paths: `coin.radius`, `effects[air_drag].viscosity` (the
// entry of `effects` whose type is air_drag), `initial[steady].theta` (`initial` when it names a
// steady motion).
import schema from 'inline:schema';

const byPath = new Map(schema.keys.map((key) => [key.path, key]));

export function schemaKey(path) {
  const key = byPath.get(path);
  if (!key) throw new Error(`page: ${path} is not a key of coinroll's scene schema`);
  return key;
}

// The schema's default for a key, or `fallback` where it has none.
export function defaultOf(path, fallback) {
  const key = schemaKey(path);
  return key.default !== undefined ? key.default : fallback;
}

// [container path segments, last name]: "effects[air_drag].length" -> [["effects[air_drag]"], "length"].
const split = (path) => {
  const parts = path.split('.');
  return [parts.slice(0, -1), parts[parts.length - 1]];
};

// The object a segment names inside `parent`, made when `create` (an effect's entry, a block).
function child(parent, segment, create) {
  const match = /^(\w+)\[(\w+)\]$/.exec(segment);
  if (!match) {
    if (parent[segment] === undefined && create) parent[segment] = {};
    return parent[segment];
  }
  const [, name, tag] = match;
  if (name === 'initial') return parent.initial && parent.initial.steady !== undefined ? parent.initial : undefined;
  if (!Array.isArray(parent[name])) {
    if (!create) return undefined;
    parent[name] = [];
  }
  let entry = parent[name].find((e) => e && e.type === tag);
  if (!entry && create) parent[name].push(entry = { type: tag });
  return entry;
}

function container(scene, path, create) {
  const [blocks] = split(path);
  let node = scene;
  for (const segment of blocks) {
    if (node === undefined || node === null || typeof node !== 'object') return undefined;
    node = child(node, segment, create);
  }
  return node;
}

export function getPath(scene, path) {
  const node = container(scene, path, false);
  return node && typeof node === 'object' ? node[split(path)[1]] : undefined;
}

export function setPath(scene, path, value) {
  container(scene, path, true)[split(path)[1]] = value;
}

export function deletePath(scene, path) {
  const node = container(scene, path, false);
  if (node && typeof node === 'object') delete node[split(path)[1]];
}

// An effect's entry in the scene's list, added or removed by a checkbox; an empty list goes away.
export const hasEffect = (scene, type) => Array.isArray(scene.effects) && scene.effects.some((e) => e && e.type === type);
export function setEffect(scene, type, on) {
  if (on && !hasEffect(scene, type)) (scene.effects = scene.effects || []).push({ type });
  if (!on && Array.isArray(scene.effects)) {
    scene.effects = scene.effects.filter((e) => !(e && e.type === type));
    if (scene.effects.length === 0) delete scene.effects;
  }
}

// Whether a presence condition of the schema holds in the scene, as the reader decides it: one of its
// paths is given and, where it lists values, that key's value (its default where absent) is one of them.
export function conditionHolds(scene, condition) {
  return condition.paths.some((path) => {
    const value = getPath(scene, path);
    if (!condition.values) return value !== undefined;
    const effective = value !== undefined ? value : schemaKey(path).default;
    return effective !== undefined && condition.values.includes(effective);
  });
}

// Whether the key may be on in the scene: its block is there (an effect's entry, a steady start) and
// its only_with and needs hold.
export function presenceHolds(scene, key) {
  if (key.path.includes('.') && container(scene, key.path, false) === undefined) return false;
  return [...(key.only_with || []), ...(key.needs || [])].every((c) => conditionHolds(scene, c));
}

export default schema;
