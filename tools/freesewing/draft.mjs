#!/usr/bin/env node
// Drafts a FreeSewing design for a measurement set and writes what Sartor's
// import tests read: the SVG exactly as FreeSewing's own renderer writes it,
// and the measurements (mm) in the body developer's measurement-file format.
//
//   node draft.mjs DESIGN (--model NAME | --measurements FILE.json) --outdir DIR
//                  [--sa MM] [--option KEY=VALUE ...] [--date YYYY-MM-DD]
//
// DESIGN is penelope, bella, aaron or teagan; NAME one of @freesewing/models'
// sets (e.g. cisFemaleAdult36). The files are DIR/DESIGN_NAME.svg and
// DIR/NAME_measurements.json.
import { writeFileSync, readFileSync, mkdirSync } from 'node:fs'
import { join } from 'node:path'
import * as models from '@freesewing/models'
import { Penelope } from '@freesewing/penelope'
import { Bella } from '@freesewing/bella'
import { Aaron } from '@freesewing/aaron'
import { Teagan } from '@freesewing/teagan'

const designs = { penelope: Penelope, bella: Bella, aaron: Aaron, teagan: Teagan }

function usage(message) {
  if (message) console.error(`draft.mjs: ${message}`)
  ;(message ? console.error : console.log)(
    'usage: node draft.mjs DESIGN (--model NAME | --measurements FILE.json) --outdir DIR [--sa MM] [--option KEY=VALUE ...] [--date YYYY-MM-DD]\n' +
      `  DESIGN: ${Object.keys(designs).join(', ')}\n` +
      '  NAME: a measurement set of @freesewing/models, e.g. cisFemaleAdult36'
  )
  process.exit(message ? 2 : 0)
}

function parseArguments(argv) {
  const args = { options: {}, sa: 0, date: '2026-11-24' }
  for (let i = 0; i < argv.length; ++i) {
    const a = argv[i]
    const value = () => {
      if (i + 1 >= argv.length) usage(`${a} needs a value`)
      return argv[++i]
    }
    if (a === '--help' || a === '-h') usage()
    else if (a === '--model') args.model = value()
    else if (a === '--measurements') args.measurementsFile = value()
    else if (a === '--outdir') args.outdir = value()
    else if (a === '--sa') args.sa = Number(value())
    else if (a === '--date') args.date = value()
    else if (a === '--option') {
      const [key, v] = value().split('=')
      args.options[key] = v === 'true' ? true : v === 'false' ? false : isNaN(Number(v)) ? v : Number(v)
    } else if (a.startsWith('-')) usage(`unknown option ${a}`)
    else if (args.design === undefined) args.design = a
    else usage(`unexpected argument ${a}`)
  }
  if (!designs[args.design]) usage(`unknown design '${args.design}'`)
  if (!args.outdir) usage('--outdir is required')
  if ((args.model === undefined) === (args.measurementsFile === undefined))
    usage('give exactly one of --model and --measurements')
  if (!(args.sa >= 0)) usage('--sa must be a number >= 0 (mm)')
  return args
}

// The measurement set, as {name, measurements} in mm (FreeSewing's unit).
function loadMeasurements(args) {
  if (args.model !== undefined) {
    if (!models[args.model] || typeof models[args.model] !== 'object' || !models[args.model].waist)
      usage(`unknown measurement set '${args.model}' in @freesewing/models`)
    return { name: args.model, measurements: models[args.model] }
  }
  const file = JSON.parse(readFileSync(args.measurementsFile, 'utf8'))
  if (file.units !== 'mm' || typeof file.measurements !== 'object')
    usage(`${args.measurementsFile}: expected {"name", "units": "mm", "measurements": {...}}`)
  return { name: file.name, measurements: file.measurements }
}

// FreeSewing's title blocks print the day of drafting (new Date() in
// @freesewing/plugin-annotations' title macro). It is pinned to the day the
// committed files were drafted, so that they regenerate byte for byte on any
// day; give another with --date YYYY-MM-DD.
function pinDraftingDate(day) {
  const pinned = Date.parse(`${day}T12:00:00Z`)
  if (Number.isNaN(pinned)) usage(`--date ${day} is not a date YYYY-MM-DD`)
  const SystemDate = Date
  globalThis.Date = class extends SystemDate {
    constructor(...when) {
      super(...(when.length > 0 ? when : [pinned]))
    }
    static now() {
      return pinned
    }
  }
}

const args = parseArguments(process.argv.slice(2))
pinDraftingDate(args.date)
const set = loadMeasurements(args)
const pattern = new designs[args.design]({
  measurements: set.measurements,
  sa: args.sa,
  complete: true,
  paperless: false,
  options: args.options,
})
const svg = pattern.draft().render()
const logs = pattern.store.logs
if (logs.error.length > 0) {
  console.error(`draft.mjs: FreeSewing reported errors drafting ${args.design}:`)
  for (const line of logs.error) console.error(`  ${line}`)
  process.exit(1)
}
mkdirSync(args.outdir, { recursive: true })
const svgFile = join(args.outdir, `${args.design}_${set.name}.svg`)
writeFileSync(svgFile, svg)
const sorted = Object.fromEntries(
  Object.keys(set.measurements)
    .sort()
    .map((k) => [k, set.measurements[k]])
)
const measurementFile = join(args.outdir, `${set.name}_measurements.json`)
writeFileSync(
  measurementFile,
  JSON.stringify({ name: set.name, units: 'mm', measurements: sorted }, null, 2) + '\n'
)
console.log(`wrote ${svgFile} and ${measurementFile}`)
